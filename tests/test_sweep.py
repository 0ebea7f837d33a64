"""Batch studies (pysolver.sweep): a grid and a Sobol sweep of seed example 3 give, case by
case, exactly the results of separate load + run calls on the edited deck; a bad path, a
failed integration, a case past its time limit and one that kills its process each get their
status while the others finish; an interrupted sweep resumes; a Dask LocalCluster gives the
same rows."""
import json

import numpy as np
import pytest

import pysolver

from helpers import DECKS

DECK = DECKS / "particle_between_lines.xml"
PEN, POS = "Force_Penalty/1/penalty", "Reference_Marker/10/pos_x"
OUT = {"x_end": "final:request/1/1", "z_min": "min:request/1/2", "steps": "steps"}


def edited(case):
    """The deck text with the case's numbers written in (the reference: load + run)."""
    text = DECK.read_text()
    text = text.replace('pos_x="100"', f'pos_x="{case[POS]!r}"')
    return text.replace('expr="1+dx(10)-dz(10)"\n                   penalty="1E4"',
                        f'expr="1+dx(10)-dz(10)"\n                   penalty="{case[PEN]!r}"')


def _same_as_separate_runs(sw, cases):
    for i, case in enumerate(cases):
        ref = pysolver.loads(edited(case)).run()
        row = sw.rows[i]
        assert row["status"] == "ok", row["message"]
        assert row["x_end"] == ref.request(1)[-1, 0]
        assert row["z_min"] == np.nanmin(ref.request(1)[:, 1])
        assert row["steps"] == ref.stats["steps"]
        np.testing.assert_array_equal(sw.result(i).request(1), ref.request(1))


def test_grid_sweep_equals_separate_runs():
    cases = pysolver.grid({PEN: [5e3, 2e4], POS: [80.0, 100.0, 110.0]})
    assert len(cases) == 6 and cases[1] == {PEN: 5e3, POS: 100.0}
    sw = pysolver.sweep(DECK, cases, processes=2, outputs=OUT)
    _same_as_separate_runs(sw, cases)
    assert sw.counts()["ok"] == 6


def test_sobol_sweep_in_process_equals_separate_runs():
    cases = pysolver.sample({PEN: (5e3, 2e4), POS: (80.0, 110.0)}, 4, seed=3)
    again = pysolver.sample({PEN: (5e3, 2e4), POS: (80.0, 110.0)}, 4, seed=3)
    assert cases == again and all(5e3 <= c[PEN] <= 2e4 for c in cases)
    sw = pysolver.sweep(DECK, cases, processes=0, outputs=OUT)
    _same_as_separate_runs(sw, cases)


def test_parameters_cover_the_model_and_reset():
    """Every listed path can be set and is put back by the next case; a case sets nothing
    else (the residual at a fixed state equals the deck's again)."""
    model = pysolver.load(DECK)
    compiled = model.compile()
    k, P = compiled.kernel, compiled.parameters
    y = k.layout.initial_state()
    base = k.residual_array(0.1, y, np.zeros_like(y))
    P.apply({PEN: 3e4, "Body_Point/2/mass": 2.5, "Force_Gravity/grav_z": -1000.0})
    assert not np.array_equal(k.residual_array(0.1, y, np.zeros_like(y)), base)
    P.apply({})
    np.testing.assert_array_equal(k.residual_array(0.1, y, np.zeros_like(y)), base)
    assert "Force_Penalty/2/smoothing_factor" in P.paths() and "Body_Point/2/v_ic_z" in P.paths()


SLOW = '''import os, signal, time


def PFOSUB(id, time_, par, npar, dflag, iflag):
    mode = float(py_sysfnc("VARVAL", [5])[0])    # float(): called from the kernel, not traced
    if mode > 1.5 and iflag == 0:
        os.kill(os.getpid(), signal.SIGSEGV)
    if mode > 0.5 and iflag == 0:
        time.sleep(60)
    return 1 + par[0] * py_sysfnc("DX", [10])[0] - py_sysfnc("DZ", [10])[0]
'''


def test_failures_get_their_status_and_the_others_finish(tmp_path):
    (tmp_path / "slow.py").write_text(SLOW)
    text = DECK.read_text().replace(
        'type="EXPRESSION" expr="1+dx(10)-dz(10)"',
        f'type="USERSUB" script_name="{tmp_path / "slow.py"}" usrsub_param_string="USER(1)"')
    text = text.replace("<Post_Request", '<Reference_Variable id="5" expr="0"/>\n    <Post_Request')
    (tmp_path / "deck.xml").write_text(text)
    cases = [{PEN: 1e4}, {"Force_Penalty/9/penalty": 1.0}, {"Reference_Variable/5/value": 1.0},
             {"Reference_Variable/5/value": 2.0}, {"Param_Transient/max_num_steps": 5},
             {PEN: "stiff"}, {PEN: 2e4}]
    sw = pysolver.sweep(tmp_path / "deck.xml", cases, processes=2, timeout=5.0)
    status = [r["status"] for r in sw.rows]
    assert status == ["ok", "error", "timeout", "crashed", "failed", "error", "ok"]
    msgs = [r["message"] for r in sw.rows]
    assert "Force_Penalty/9/penalty" in msgs[1] and "unknown" not in msgs[0]
    assert "stopped after 5 s" in msgs[2] and "SIGSEGV" in msgs[3]
    assert "got 'stiff'; expected a real number" in msgs[5]
    assert sw.result(1) is None and sw.result(6).success


def test_resume_after_an_interrupted_sweep(tmp_path):
    cases = pysolver.grid({PEN: [5e3, 1e4], POS: [90.0, 100.0]})
    first = pysolver.sweep(DECK, cases, processes=0, directory=tmp_path, outputs=OUT)
    lines = (tmp_path / "cases.jsonl").read_text().splitlines()
    # an interruption: the last case's line never written, the third cut halfway
    (tmp_path / "cases.jsonl").write_text("\n".join(lines[:2] + [lines[2][:30]]) + "\n")
    again = pysolver.sweep(DECK, cases, processes=0, directory=tmp_path, outputs=OUT)
    assert [r["resumed"] for r in again.rows] == [True, True, False, False]
    for a, b in zip(first.rows, again.rows):
        assert a["x_end"] == b["x_end"] and a["status"] == b["status"] == "ok"
    keys = [json.loads(x)["key"] for x in (tmp_path / "cases.jsonl").read_text().splitlines()
            if x.startswith("{") and x.endswith("}")]
    assert len(set(keys)) == 4
    np.testing.assert_array_equal(again.result(3).request(1), first.result(3).request(1))


def test_dask_local_cluster_equals_the_process_run():
    distributed = pytest.importorskip("dask.distributed", reason="the dask extra")
    cases = pysolver.grid({PEN: [5e3, 2e4], POS: [90.0, 100.0]})
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        sw = pysolver.sweep(DECK, cases, client=client, outputs=OUT)
    ref = pysolver.sweep(DECK, cases, processes=0, outputs=OUT)
    for a, b in zip(sw.rows, ref.rows):
        assert (a["status"], a["x_end"], a["z_min"], a["steps"]) == \
            (b["status"], b["x_end"], b["z_min"], b["steps"])


def test_bad_outputs_are_refused_before_any_case_runs():
    with pytest.raises(ValueError, match="no channel 'request/7/1'"):
        pysolver.sweep(DECK, [{}], processes=0, outputs={"a": "final:request/7/1"})
    with pytest.raises(ValueError, match="FUNC one of final, max, min, mean"):
        pysolver.sweep(DECK, [{}], processes=0, outputs={"a": "median:request/1/1"})


def test_cli_sweep_writes_the_table_and_resumes(tmp_path, capsys):
    from pysolver.cli import main
    args = ["sweep", str(DECK), "--set", f"{PEN}=5e3,1e4", "--set", f"{POS}=90,100",
            "--output", "x_end=final:request/1/1", "-j", "0", "-o", str(tmp_path), "-q"]
    assert main(args) == 0
    import csv
    with open(tmp_path / "table.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["status"] for r in rows] == ["ok"] * 4 and len(list(tmp_path.glob("results/*"))) == 4
    ref = pysolver.loads(edited({PEN: 1e4, POS: 90.0})).run()
    assert float(rows[2]["x_end"]) == ref.request(1)[-1, 0]
    assert main(args) == 0
    with open(tmp_path / "table.csv", newline="") as fh:
        assert all(r["resumed"] == "True" for r in csv.DictReader(fh))
    bad = ["sweep", str(DECK), "--set", "Force_Penalty/7/penalty=1,2", "-j", "0", "-o",
           str(tmp_path / "bad"), "-q"]
    assert main(bad) == 1
    sampled = ["sweep", str(DECK), "--set", f"{PEN}=5e3,2e4", "--sample", "lhs:3", "--seed",
               "1", "-j", "0", "-o", str(tmp_path / "lhs"), "-q"]
    assert main(sampled) == 0
    capsys.readouterr()


def test_a_gravity_case_runs_as_a_deck_with_that_gravity():
    """A case's gravity reaches the joints' compliance, which follows the bodies' weight
    (pysolver.build.consistent): the revolute pendulum under grav_y = -100 gives, bit for
    bit, the answers of a deck written with that gravity (the compliance once stayed at the
    deck's -9.81)."""
    text = (DECKS / "joints" / "pendulum_revolute.xml").read_text()
    heavy = text.replace('grav_y="-9.81"', 'grav_y="-100"')
    assert heavy != text
    model = pysolver.loads(text)
    model.run()
    res = model.run(params={"Force_Gravity/grav_y": -100.0})
    ref = pysolver.loads(heavy).run()
    np.testing.assert_array_equal(res.y, ref.y)
    assert res.stats == ref.stats
