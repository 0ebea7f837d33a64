"""Issue 22, items 8-15: a stored row is always the current deck's result, and only finished
work is stored.

8  the resume key covers the files a deck names (script, C library), pysolver's version and
   the outputs;                                9  non-ok rows run again on resume (keep= keeps);
10 a storage error stops the sweep with its message, Ctrl-C stores nothing of the case it
   stopped (in this process and in workers), a crash is ``crashed`` on Dask too;
11 a case's value obeys the deck's rules;      12 nothing runs user code in the parent;
13 a plain script (no ``if __name__``) sweeps;  14 the table without pandas;
15 a damaged study folder: damaged entries are cases not run; the client writes the results.
"""
import errno
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

import pysolver
from pysolver.batch import StorageError, store
from pysolver.build.params import check_value

from helpers import DECKS

DECK = DECKS / "particle_between_lines.xml"
PEN, POS = "Force_Penalty/1/penalty", "Reference_Marker/10/pos_x"
MODE = "Reference_Variable/5/value"
OUT = {"x_end": "final:request/1/1", "z_min": "min:request/1/2"}
ENV = dict(os.environ, PYTHONPATH=str(pathlib.Path(pysolver.__file__).parents[1]))


def usersub_deck(tmp_path, script, name="sub.py"):
    """Seed example 3 with line 1 given by a Python PFOSUB (USER(1): g = par + x - z) and a
    named number (Reference_Variable 5, the case's "mode") the routine may read."""
    (tmp_path / name).write_text(textwrap.dedent(script))
    text = DECK.read_text().replace(
        'type="EXPRESSION" expr="1+dx(10)-dz(10)"',
        f'type="USERSUB" script_name="{tmp_path / name}" usrsub_param_string="USER(1)"')
    text = text.replace("<Post_Request", '<Reference_Variable id="5" expr="0"/>\n    '
                                         "<Post_Request")
    deck = tmp_path / f"{pathlib.Path(name).stem}.xml"
    deck.write_text(text)
    return deck


TRACED = '''
def PFOSUB(id, time_, par, npar, dflag, iflag):
    return OFFSET * par[0] + py_sysfnc("DX", [10])[0] - py_sysfnc("DZ", [10])[0]


OFFSET = 1.0
'''

#: A routine the kernel calls (float() keeps it from being traced): mode 1 sleeps `SLEEP` s
#: once per process, mode 2 kills its process, mode 3 sends SIGINT to it (Ctrl-C).
CALLED = '''
import os, signal, time
done = []


def PFOSUB(id, time_, par, npar, dflag, iflag):
    mode = float(py_sysfnc("VARVAL", [5])[0])
    if iflag == 0 and mode > 0.5 and not done:
        done.append(1)
        if mode < 1.5:
            time.sleep(SLEEP)
        elif mode < 2.5:
            os.kill(os.getpid(), signal.SIGSEGV)
        else:
            os.kill(os.getpid(), signal.SIGINT)
    return par[0] + py_sysfnc("DX", [10])[0] - py_sysfnc("DZ", [10])[0]


SLEEP = 60
'''


def lines(directory):
    return [json.loads(x) for x in (directory / "cases.jsonl").read_text().splitlines() if x]


# 8 ------------------------------------------------------------------------------------------
def test_resume_key_covers_the_script_the_version_and_the_outputs(tmp_path, monkeypatch):
    """Editing the user subroutine script (the deck text unchanged) makes a resume run the
    cases again, with the edited routine; so do another pysolver version and other outputs.
    With nothing changed the rows are reused."""
    deck = usersub_deck(tmp_path, TRACED)
    study = tmp_path / "study"
    cases = [{PEN: 1e4}, {PEN: 2e4}]
    out = {"z_end": "final:request/1/2"}
    first = pysolver.sweep(deck, cases, processes=0, directory=study, outputs=out)
    same = pysolver.sweep(deck, cases, processes=0, directory=study, outputs=out)
    assert [r["resumed"] for r in same.rows] == [True, True]
    (tmp_path / "sub.py").write_text(TRACED.replace("OFFSET = 1.0", "OFFSET = 3.0"))
    edited = pysolver.sweep(deck, cases, processes=0, directory=study, outputs=out)
    assert [r["resumed"] for r in edited.rows] == [False, False]
    for a, b in zip(first.rows, edited.rows):
        # the particle rests where the lines z = OFFSET + x and z = 1 - x meet (less the
        # penalties' give): z = (1 + OFFSET) / 2
        assert b["z_end"] - a["z_end"] == pytest.approx(1.0, abs=1e-3)
    ref = pysolver.load(deck).run()          # a fresh load + run of the edited deck
    assert edited.rows[0]["z_end"] == ref.request(1)[-1, 1]
    np.testing.assert_array_equal(edited.result(0).request(1), ref.request(1))
    again = pysolver.sweep(deck, cases, processes=0, directory=study,
                           outputs={**out, "x_end": "final:request/1/1"})
    assert [r["resumed"] for r in again.rows] == [False, False]
    monkeypatch.setattr("pysolver.batch.case.__version__", "99.0")
    newer = pysolver.sweep(deck, cases, processes=0, directory=study, outputs=out)
    assert [r["resumed"] for r in newer.rows] == [False, False]


C_LINE = r"""
#include "pysolver_usersub.h"
void LINE(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
          double *value) {
  int m = 10, err;
  double x, z;
  c_sysfnc("DX", &m, 1, &x, &err);
  c_sysfnc("DZ", &m, 1, &z, &err);
  *value = OFFSET + x - z;
}
"""


def test_resume_key_covers_a_c_library(tmp_path):
    """Rebuilding the C library a deck names makes a resume run the cases again, in worker
    processes that have not loaded the old library."""
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        pytest.skip("no C compiler to build the test's library")

    def build(offset):
        (tmp_path / "line.c").write_text(C_LINE)
        subprocess.run([cc, "-shared", "-fPIC", f"-DOFFSET={offset}",
                        f"-I{pysolver.get_include()}", str(tmp_path / "line.c"), "-o",
                        str(tmp_path / "line.so")], check=True)
    build("1.0")
    text = DECK.read_text().replace(
        'type="EXPRESSION" expr="1+dx(10)-dz(10)"',
        f'type="USERSUB" usrsub_dll_name="{tmp_path / "line.so"}" usrsub_fnc_name="LINE"')
    (tmp_path / "deck.xml").write_text(text)
    cases, out = [{PEN: 1e4}, {PEN: 2e4}], {"z_end": "final:request/1/2"}
    first = pysolver.sweep(tmp_path / "deck.xml", cases, processes=2, directory=tmp_path / "s",
                           outputs=out)
    assert [r["status"] for r in first.rows] == ["ok", "ok"]
    build("3.0")
    again = pysolver.sweep(tmp_path / "deck.xml", cases, processes=2, directory=tmp_path / "s",
                           outputs=out)
    assert [r["resumed"] for r in again.rows] == [False, False]
    for a, b in zip(first.rows, again.rows):
        assert b["z_end"] - a["z_end"] == pytest.approx(1.0, abs=1e-3)


# 9 ------------------------------------------------------------------------------------------
def test_cases_that_did_not_finish_ok_run_again_on_resume(tmp_path):
    """A case that timed out runs again when the sweep is repeated with a longer time limit
    (and a failed one too); keep="all" keeps the stored rows instead."""
    deck = usersub_deck(tmp_path, CALLED.replace("SLEEP = 60", "SLEEP = 3"))
    study = tmp_path / "study"
    cases = [{MODE: 0.0}, {MODE: 1.0}, {"Param_Transient/max_num_steps": 5}]
    first = pysolver.sweep(deck, cases, processes=2, timeout=1.0, directory=study)
    assert [r["status"] for r in first.rows] == ["ok", "timeout", "failed"]
    kept = pysolver.sweep(deck, cases, processes=2, timeout=120, directory=study, keep="all")
    assert [(r["status"], r["resumed"]) for r in kept.rows] == \
        [("ok", True), ("timeout", True), ("failed", True)]
    again = pysolver.sweep(deck, cases, processes=2, timeout=120, directory=study)
    assert [(r["status"], r["resumed"]) for r in again.rows] == \
        [("ok", True), ("ok", False), ("failed", False)]
    assert again.rows[1]["message"] == "The simulation finished." and again.result(1).success
    assert "max_num_steps" in again.rows[2]["message"] or "steps" in again.rows[2]["message"]
    # the last line of a case wins: a third run reuses the case that now finished
    third = pysolver.sweep(deck, cases, processes=2, timeout=120, directory=study)
    assert [r["resumed"] for r in third.rows] == [True, True, False]
    with pytest.raises(ValueError, match="keep: unknown status 'done'"):
        pysolver.sweep(deck, cases, processes=0, directory=study, keep=("ok", "done"))


# 10 -----------------------------------------------------------------------------------------
def test_a_storage_error_stops_the_sweep_with_its_message(tmp_path, monkeypatch):
    """A full disk while a Result is written: the sweep stops with the error (the file, the
    reason), the cases stored before it stay, no row says the case crashed; the sweep then
    resumes. The results are written by this process, so the worker processes never see the
    error."""
    cases = pysolver.grid({PEN: [5e3, 1e4, 2e4, 4e4]})
    real, calls = store._write_file, []

    def full(path, blob):
        calls.append(path)
        if len(calls) == 3:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        real(path, blob)
    monkeypatch.setattr(store, "_write_file", full)
    with pytest.raises(StorageError) as info:
        pysolver.sweep(DECK, cases, processes=2, directory=tmp_path, outputs=OUT)
    msg = str(info.value)
    assert msg.startswith(f"cannot write {tmp_path / 'results'}") and \
        "No space left on device; the sweep stopped (2 cases stored by this run" in msg
    assert info.value.errno == errno.ENOSPC
    stored = lines(tmp_path)
    assert len(stored) == 2 and {r["status"] for r in stored} == {"ok"}
    monkeypatch.setattr(store, "_write_file", real)
    again = pysolver.sweep(DECK, cases, processes=2, directory=tmp_path, outputs=OUT)
    assert [r["status"] for r in again.rows] == ["ok"] * 4
    assert sum(r["resumed"] for r in again.rows) == 2
    # a cases.jsonl that cannot be opened: stopped before any case runs
    bad = tmp_path / "bad"
    (bad / "cases.jsonl").mkdir(parents=True)
    with pytest.raises(StorageError, match="cannot use .*cases.jsonl: Is a directory"):
        pysolver.sweep(DECK, cases, processes=0, directory=bad)


def test_an_unwritable_results_folder_stops_the_sweep(tmp_path, monkeypatch):
    pysolver.sweep(DECK, [{PEN: 5e3}], processes=0, directory=tmp_path)
    (tmp_path / "results").chmod(0o500)
    if os.geteuid() == 0:         # root writes into read-only folders: fail as others would

        def denied(path, blob):
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(path))
        monkeypatch.setattr(store, "_write_file", denied)
    try:
        with pytest.raises(StorageError, match="cannot write .*Permission denied; the sweep "
                                               "stopped"):
            pysolver.sweep(DECK, [{PEN: 1e4}], processes=2, directory=tmp_path)
    finally:
        (tmp_path / "results").chmod(0o700)
    assert [r["status"] for r in lines(tmp_path)] == ["ok"]


def test_ctrl_c_stops_an_in_process_sweep_and_stores_nothing_of_its_case(tmp_path):
    """processes=0: Ctrl-C during the second case (the routine signals its own process)
    raises KeyboardInterrupt; the first case is stored, the second is not (it was stored as
    "failed" before), the third never ran. The sweep resumes from there."""
    deck = usersub_deck(tmp_path, CALLED)
    cases = [{MODE: 0.0}, {MODE: 3.0}, {MODE: 0.0, PEN: 2e4}]
    with pytest.raises(KeyboardInterrupt):
        pysolver.sweep(deck, cases, processes=0, directory=tmp_path / "s")
    stored = lines(tmp_path / "s")
    assert [r["status"] for r in stored] == ["ok"] and len(stored) == 1
    again = pysolver.sweep(deck, [cases[0], cases[2]], processes=0, directory=tmp_path / "s")
    assert [(r["status"], r["resumed"]) for r in again.rows] == [("ok", True), ("ok", False)]


def test_ctrl_c_stops_a_process_sweep_and_stores_nothing_of_the_running_case(tmp_path):
    """Ctrl-C (SIGINT to this process) while a worker runs a 60 s case: KeyboardInterrupt,
    the finished case stored, the running one not."""
    deck = usersub_deck(tmp_path, CALLED)
    study = tmp_path / "s"
    cases = [{MODE: 0.0}, {MODE: 1.0}]
    done = threading.Event()

    def interrupt():
        for _ in range(1200):                   # up to 60 s for the first case
            if done.wait(0.05):
                return
            if (study / "cases.jsonl").exists() and lines(study):
                os.kill(os.getpid(), signal.SIGINT)
                return
    watcher = threading.Thread(target=interrupt)
    watcher.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            pysolver.sweep(deck, cases, processes=1, directory=study)
    finally:
        done.set()
        watcher.join()
    assert [r["status"] for r in lines(study)] == ["ok"]


def test_dask_crash_is_crashed_and_the_healthy_cases_finish(tmp_path):
    """On a Dask LocalCluster: the case that kills its process is `crashed` (SIGSEGV), the
    one past the time limit `timeout`, every healthy case `ok` with the numbers of an
    in-process run."""
    distributed = pytest.importorskip("dask.distributed", reason="the dask extra")
    deck = usersub_deck(tmp_path, CALLED)
    cases = [{MODE: 0.0}, {MODE: 2.0}, {MODE: 0.0, PEN: 2e4}, {MODE: 1.0},
             {MODE: 0.0, PEN: 5e3}]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        sw = pysolver.sweep(deck, cases, client=client, timeout=3.0, outputs=OUT,
                            directory=tmp_path / "s")
    assert [r["status"] for r in sw.rows] == ["ok", "crashed", "ok", "timeout", "ok"]
    assert "killed by signal SIGSEGV" in sw.rows[1]["message"]
    assert sw.rows[3]["message"] == "stopped after 3 s"
    ref = pysolver.sweep(deck, [cases[0], cases[2], cases[4]], processes=0, outputs=OUT)
    for a, b in zip([sw.rows[0], sw.rows[2], sw.rows[4]], ref.rows):
        assert (a["x_end"], a["z_min"], a["steps"]) == (b["x_end"], b["z_min"], b["steps"])
    assert len(list((tmp_path / "s" / "results").glob("*.pkl"))) == 3


# 11 -----------------------------------------------------------------------------------------
BAD = [(PEN, -1e4, "got -10000; expected a value > 0", 'penalty="-1e4"'),
       (PEN, 0, "got 0; expected a value > 0", 'penalty="0"'),
       ("Force_Penalty/1/smoothing_factor", 0, "got 0; expected a value > 0",
        'smoothing_factor="0"'),
       ("Force_Penalty/1/smoothing_factor", -1, "got -1; expected a value > 0",
        'smoothing_factor="-1"'),
       (PEN, True, "got True; expected a real number", None),
       ("Param_Transient/max_num_steps", 2.5, "got 2.5; expected a positive integer",
        'integr_tol="1e-6" max_num_steps="2.5"'),
       ("Body_Point/2/mass", -1.0, "got -1; expected a value > 0", 'mass="-1.0"'),
       ("Param_Transient/nonlin_conv_coef", 2.0, "got 2; expected a value in (0, 1)", None)]


def _deck_with(attr):
    text = DECK.read_text()
    key = attr.split("=")[0]
    if key == "integr_tol":
        return text.replace('integr_tol="1e-6"', attr)
    if key == "mass":
        return text.replace('mass="1.0"', attr)
    if key == "penalty":
        return text.replace('penalty="1E4" penalty1="1E2" unilateral="True" smoothing_factor='
                            '"1.0"/>\n    <Force_Penalty id="2"', f'{attr} penalty1="1E2" '
                            'unilateral="True" smoothing_factor="1.0"/>\n    <Force_Penalty '
                            'id="2"')
    return text.replace('smoothing_factor="1.0"/>\n    <Force_Penalty id="2"',
                        f'{attr}/>\n    <Force_Penalty id="2"')


def test_case_values_obey_the_decks_rules():
    """Each bad value is an `error` row (no run: penalty -1e4 ran to z = -2.4e126 before)
    with the loader's reason; the same value as the deck's text (as a CSV of cases gives it)
    gets exactly the DeckError reason the deck gets. The good case runs."""
    cases = [{PEN: 1e4}] + [{path: value} for path, value, _, _ in BAD]
    sw = pysolver.sweep(DECK, cases, processes=0, outputs=OUT)
    assert sw.rows[0]["status"] == "ok" and sw.rows[0]["z_min"] > 0
    for row, (path, value, reason, _) in zip(sw.rows[1:], BAD):
        assert row["status"] == "error", (path, value)
        assert row["message"].endswith(f"sweep parameter {path!r}: {reason}"), row["message"]
        assert row["z_min"] is None and row["steps"] is None      # no run, no outputs
    assert sw.result(1) is None
    texts = [(path, attr) for path, _, _, attr in BAD if attr is not None]
    as_text = pysolver.sweep(DECK, [{p: a.split('"')[-2]} for p, a in texts], processes=0)
    for row, (path, attr) in zip(as_text.rows, texts):
        with pytest.raises(pysolver.DeckError) as info:
            pysolver.loads(_deck_with(attr))
        assert row["status"] == "error"
        assert row["message"].endswith(f"sweep parameter {path!r}: {info.value.reason}")


def test_every_sweep_path_has_the_decks_rule():
    """check_value knows every path a case may set (no path without a rule) and converts as
    the loader does: a whole number of steps in E notation is an int, "1D4" a number."""
    model = pysolver.load(DECKS / "particle_between_lines.xml")
    params = model.compile().parameters
    for path in params.paths():
        try:
            check_value(path, 0.5)
        except pysolver.DeckError as err:
            assert path in str(err)
    assert check_value("Param_Transient/max_num_steps", "1e3") == 1000
    assert check_value(PEN, "1D4") == 1e4
    with pytest.raises(pysolver.DeckError, match="expected \\|grav_z\\| <= 1e\\+20"):
        check_value("Force_Gravity/grav_z", -1e30)


# 12 -----------------------------------------------------------------------------------------
KILLER = '''
import os, signal
os.kill(os.getpid(), signal.SIGSEGV)        # runs when the model is compiled


def PFOSUB(id, time_, par, npar, dflag, iflag):
    return par[0]
'''


def test_a_crashing_routine_never_runs_in_the_parent(tmp_path):
    """An output naming a state compiled the model in the parent: a routine crashing at
    compile time killed it (no rows). Now every case is `crashed` and the parent reports."""
    deck = usersub_deck(tmp_path, KILLER)
    (tmp_path / "study.py").write_text(textwrap.dedent(f'''
        import json, pysolver
        sw = pysolver.sweep({str(deck)!r}, [{{}}, {{{PEN!r}: 2e4}}], processes=2,
                            outputs={{"zmax": "max:body2.z"}})
        print(json.dumps([[r["status"], r["message"]] for r in sw.rows]))
        print(sw.result(0))
        sw = pysolver.sweep({str(deck)!r}, [{{}}] * 5, processes=1)
        print(json.dumps([[r["status"], r["message"]] for r in sw.rows]))
    '''))
    out = subprocess.run([sys.executable, "study.py"], cwd=tmp_path, env=ENV,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    rows = json.loads(out.stdout.splitlines()[0])
    assert [r[0] for r in rows] == ["crashed", "crashed"]
    assert all(r[1] == "the worker process died (killed by signal SIGSEGV)" for r in rows)
    assert out.stdout.splitlines()[1] == "None"
    # three workers in a row killed while loading the model: the other cases are not tried
    rows = json.loads(out.stdout.splitlines()[2])
    assert [r[0] for r in rows] == ["crashed"] * 5
    assert [r[1] for r in rows[3:]] == ["not run: the worker process died while loading and "
                                        "compiling the model, 3 times in a row (the last: "
                                        "killed by signal SIGSEGV)"] * 2
    # here too: a process sweep with a state output, and a Result fetched again, leave this
    # process's model uncompiled (the workers compiled theirs)
    model = pysolver.load(DECK)
    sw = pysolver.sweep(model, [{PEN: 2e4}], processes=1, outputs={"zmax": "max:body2.z"})
    assert sw.rows[0]["status"] == "ok" and sw.result(0).success
    assert model.compiled_kernels == ()


# 13 -----------------------------------------------------------------------------------------
def test_a_plain_script_sweeps_without_a_main_guard(tmp_path):
    """No `if __name__ == "__main__":`: the workers never import the script (it prints once),
    no RuntimeError, every case ok with the numbers of an in-process sweep; a function of
    the main script as an output reaches the workers."""
    cases = pysolver.grid({PEN: [5e3, 2e4], POS: [90.0, 100.0]})
    (tmp_path / "plain.py").write_text(textwrap.dedent(f'''
        import json, pysolver
        print("the main script runs")
        def x_end(res):
            return res.request(1)[-1, 0]
        sw = pysolver.sweep({str(DECK)!r}, {cases!r}, processes=2,
                            outputs={{"x_end": x_end, "z_min": "min:request/1/2"}})
        print(json.dumps(sw.rows))
    '''))
    out = subprocess.run([sys.executable, "plain.py"], cwd=tmp_path, env=ENV,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "RuntimeError" not in out.stderr and "Traceback" not in out.stderr
    assert out.stdout.count("the main script runs") == 1
    rows = json.loads(out.stdout.splitlines()[-1])
    ref = pysolver.sweep(DECK, cases, processes=0, outputs=OUT)
    assert [r["status"] for r in rows] == ["ok"] * 4
    for a, b in zip(rows, ref.rows):
        assert (a["x_end"], a["z_min"], a["steps"]) == (b["x_end"], b["z_min"], b["steps"])


# 14 -----------------------------------------------------------------------------------------
def test_the_table_works_without_pandas(tmp_path, monkeypatch, capsys):
    """With pandas unimportable: Sweep.table gives the columns (NumPy arrays) and prints;
    to_dataframe() says what it needs; the command line writes table.csv."""
    monkeypatch.setitem(sys.modules, "pandas", None)
    cases = pysolver.grid({PEN: [5e3, 2e4], POS: [90.0, 100.0]}) + [{PEN: -1.0}]
    sw = pysolver.sweep(DECK, cases, processes=0, outputs=OUT)
    t = sw.table
    assert list(t)[:3] == ["case", PEN, POS] and "resumed" in t
    assert list(t["status"]) == ["ok"] * 4 + ["error"]
    assert (t["status"] == "ok").sum() == 4
    np.testing.assert_array_equal(t["x_end"][:4], [r["x_end"] for r in sw.rows[:4]])
    assert np.isnan(t["x_end"][4]) and t["case"].tolist() == [0, 1, 2, 3, 4]
    text = str(t)
    assert text.splitlines()[0].split()[:3] == ["case", PEN, POS]
    assert text.splitlines()[-1] == f"[5 rows x {len(t)} columns]"
    with pytest.raises(ImportError, match="needs pandas \\(pip install pandas"):
        sw.to_dataframe()
    from pysolver.cli import main
    assert main(["sweep", str(DECK), "--set", f"{PEN}=5e3,1e4", "-j", "0", "-o",
                 str(tmp_path), "-q"]) == 0
    assert (tmp_path / "table.csv").read_text().splitlines()[0].startswith(f"case,{PEN},status")
    capsys.readouterr()


def test_the_table_as_a_dataframe():
    pd = pytest.importorskip("pandas")
    cases = pysolver.grid({PEN: [5e3, 2e4]})
    sw = pysolver.sweep(DECK, cases, processes=0, outputs=OUT)
    df = sw.to_dataframe()
    assert isinstance(df, pd.DataFrame) and df.index.name == "case"
    assert df["x_end"].tolist() == [r["x_end"] for r in sw.rows]
    assert pd.DataFrame(sw.table).shape == (2, len(sw.table))


# 15 -----------------------------------------------------------------------------------------
def test_a_damaged_study_folder_reruns_the_damaged_cases(tmp_path):
    """Non-UTF-8, non-JSON and non-row lines in cases.jsonl are skipped; a case whose Result
    is truncated or missing runs again; a Result damaged after the sweep is run again by
    Sweep.result. `results` a file, or the folder a file, is a StorageError at once."""
    cases = pysolver.grid({PEN: [5e3, 1e4, 2e4, 4e4]})
    first = pysolver.sweep(DECK, cases, processes=0, directory=tmp_path, outputs=OUT)
    with open(tmp_path / "cases.jsonl", "ab") as fh:
        fh.write(b"\xff\xfe\x00garbage\nnot json\n[1, 2]\n{\"status\": \"ok\"}\n"
                 b"{\"key\": \"x\", \"status\": \"fine\"}\n{\"key\": \"cut")
    pkl = {i: tmp_path / "results" / f"{k}.pkl" for i, k in enumerate(first.keys)}
    pkl[1].write_bytes(pkl[1].read_bytes()[:100])
    pkl[2].unlink()
    again = pysolver.sweep(DECK, cases, processes=2, directory=tmp_path, outputs=OUT)
    assert [r["resumed"] for r in again.rows] == [True, False, False, True]
    for a, b in zip(first.rows, again.rows):
        assert (a["status"], a["x_end"], a["z_min"]) == (b["status"], b["x_end"], b["z_min"])
    np.testing.assert_array_equal(again.result(1).request(1), first.result(1).request(1))
    raw = bytearray(pkl[3].read_bytes())
    raw[len(raw) // 2] ^= 0xFF                   # same size, other bytes
    pkl[3].write_bytes(bytes(raw))
    np.testing.assert_array_equal(again.result(3).request(1), first.result(3).request(1))
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "results").write_text("")
    with pytest.raises(StorageError, match="results is a file, not a folder"):
        pysolver.sweep(DECK, cases, processes=0, directory=tmp_path / "other")
    (tmp_path / "afile").write_text("")
    with pytest.raises(StorageError, match="afile is a file, not a folder"):
        pysolver.sweep(DECK, cases, processes=0, directory=tmp_path / "afile")


def test_dask_workers_do_not_write_into_the_study_folder(tmp_path, monkeypatch):
    """A Dask worker whose working folder is not the client's: the sweep's relative directory
    holds every Result (the client wrote them), the worker's folder nothing (it wrote
    there before, and each case was `error`)."""
    distributed = pytest.importorskip("dask.distributed", reason="the dask extra")
    (tmp_path / "client").mkdir()
    (tmp_path / "worker").mkdir()
    monkeypatch.chdir(tmp_path / "worker")
    cases = pysolver.grid({PEN: [5e3, 1e4, 2e4]})
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        monkeypatch.chdir(tmp_path / "client")
        sw = pysolver.sweep(DECK, cases, client=client, outputs=OUT, directory="study")
    assert [r["status"] for r in sw.rows] == ["ok"] * 3
    assert len(list((tmp_path / "client" / "study" / "results").glob("*.pkl"))) == 3
    assert list((tmp_path / "worker").iterdir()) == []
    np.testing.assert_array_equal(sw.result(2).request(1),
                                  pysolver.sweep(DECK, cases[2:], processes=0).result(0)
                                  .request(1))


def test_a_runs_statistics_do_not_depend_on_the_runs_before():
    """A joint deck's runs with the same numbers give the same rows and the same statistics,
    whatever ran before (a run of other numbers recomputes the joints' compliance, whose
    Jacobians were counted as the next run's before stop 37: njac 278, then 280)."""
    model = pysolver.load(DECKS / "joints" / "pendulum_revolute.xml")
    case = {"Body_Rigid/2/mass": 2.0}
    first, heavy = model.run(progress=False), model.run(progress=False, params=case)
    again, heavy_again = model.run(progress=False), model.run(progress=False, params=case)
    for a, b in ((first, again), (heavy, heavy_again)):
        assert a.stats == b.stats
        assert np.array_equal(a.y, b.y)


HANGS = '''
def PFOSUB(id, time_, par, npar, dflag, iflag):
    while True:
        pass
'''


def test_a_model_that_never_compiles_stops_after_two_workers(tmp_path):
    """A routine that never returns when it is traced (at the worker's compile; the parent
    compiles nothing): each worker gets startup_timeout, not the case's timeout; after two in a
    row the cases not yet run are rows at once (trial 44, defect 5)."""
    deck = usersub_deck(tmp_path, HANGS)
    cases = [{PEN: 1e4 + i} for i in range(5)]
    sw = pysolver.sweep(deck, cases, processes=1, timeout=1.0, startup_timeout=1.5)
    stopped = "stopped: the worker did not load and compile the model within 1.5 s"
    not_run = ("not run: the model did not finish loading and compiling in a worker within "
               "1.5 s, 2 times in a row (a deck, user subroutine or compiler that hangs; "
               "startup_timeout=, --startup-timeout, sets the allowance)")
    assert [(r["status"], r["message"]) for r in sw.rows] == \
        [("timeout", stopped)] * 2 + [("timeout", not_run)] * 3
    from pysolver.cli import main
    assert main(["sweep", str(deck), "--set", f"{PEN}=1e4,2e4,3e4", "-j", "1", "--timeout",
                 "1", "--startup-timeout", "1.5", "-o", str(tmp_path / "cli"), "-q"]) == 1
    table = (tmp_path / "cli" / "table.csv").read_text().splitlines()
    assert [line.split(",")[2] for line in table[1:]] == ["timeout"] * 3


def test_the_startup_allowance_and_its_default():
    """Without startup_timeout: no limit without a timeout, else the larger of the timeout and
    pool.STARTUP; a startup_timeout that is not a positive number is refused."""
    from pysolver.batch import pool
    payload = ("fp", b"", True)
    assert pool.Pool(payload, 1).startup is None
    assert pool.Pool(payload, 1, timeout=2.0).startup == pool.STARTUP == 300.0
    assert pool.Pool(payload, 1, timeout=900.0).startup == 900.0
    assert pool.Pool(payload, 1, timeout=2.0, startup=5.0).startup == 5.0
    for bad in (0, -1.0, float("nan"), True, "10"):
        with pytest.raises(ValueError) as err:
            pysolver.sweep(DECK, [{PEN: 1e4}], processes=0, startup_timeout=bad)
        assert str(err.value) == f"startup_timeout: got {bad!r}; expected a number of " \
                                 "seconds > 0"
