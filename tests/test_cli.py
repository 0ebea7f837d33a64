"""The pysolver command: one line `pysolver: error: ...` and exit 2 for every user error, a
quiet end when its reader goes away, --version and --help, one spelling of the output folder,
default folders that do not overwrite another deck's, --states / --npz, statics in the summary
and stats.json, and no scikit-sundae or scipy.optimize in a C-backend run."""
import csv
import json
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

import pysolver
from pysolver.cli import main

from helpers import DECKS, TEST_DECKS

DECK = DECKS / "particle_between_lines.xml"
PEN = "Force_Penalty/1/penalty"
SRC = str(pathlib.Path(pysolver.__file__).resolve().parents[1])


def _error(capsys, argv):
    """Run main(argv); its exit status and the lines of standard error."""
    status = main([str(a) for a in argv])
    return status, capsys.readouterr().err.strip().splitlines()


def _cli(*args, cwd):
    env = dict(os.environ, PYTHONPATH=SRC)
    return subprocess.run([sys.executable, "-m", "pysolver", *map(str, args)], cwd=cwd,
                          env=env, capture_output=True, text=True)


# user errors: exit 2 and one line ------------------------------------------------------------

def test_a_cell_of_cases_that_is_no_number(tmp_path, capsys):
    cases = tmp_path / "cases.csv"
    cases.write_text(f"{PEN}\n5e3\nabc\n")
    assert _error(capsys, ["sweep", DECK, "--cases", cases, "-o", tmp_path / "s"]) == (2, [
        f"pysolver: error: --cases {cases}: row 3, column '{PEN}': 'abc' is not a number"])
    assert not (tmp_path / "s").exists()


def test_an_empty_design(tmp_path, capsys):
    header = tmp_path / "header.csv"
    header.write_text(f"{PEN}\n")
    assert _error(capsys, ["sweep", DECK, "--cases", header, "-o", tmp_path / "s"]) == (2, [
        f"pysolver: error: --cases {header}: no cases (a header and no rows)"])
    empty = tmp_path / "empty.csv"
    empty.write_text("")
    assert _error(capsys, ["sweep", DECK, "--cases", empty, "-o", tmp_path / "s"]) == (2, [
        f"pysolver: error: --cases {empty}: empty file (expected a header of paths and a row "
        "per case)"])
    assert _error(capsys, ["sweep", DECK, "-o", tmp_path / "s"]) == (2, [
        "pysolver: error: no cases: give --set PATH=V1,V2,... (a grid), --sample with --set "
        "ranges, or --cases CSV"])


def test_a_sample_of_no_cases(tmp_path, capsys):
    base = ["sweep", DECK, "--set", f"{PEN}=5e3,2e4", "-o", tmp_path / "s"]
    assert _error(capsys, base + ["--sample", "sobol:0"]) == (2, [
        "pysolver: error: --sample sobol:0: N must be at least 1"])
    assert _error(capsys, base + ["--sample", "halton:4"]) == (2, [
        "pysolver: error: --sample 'halton:4': expected sobol:N or lhs:N"])


def test_an_unreachable_scheduler_fails_after_five_seconds(tmp_path, capsys):
    pytest.importorskip("dask.distributed", reason="the dask extra")
    argv = ["sweep", DECK, "--set", f"{PEN}=5e3,2e4", "--scheduler", "tcp://127.0.0.1:1",
            "-o", tmp_path / "s", "-q"]
    assert _error(capsys, argv) == (2, [
        "pysolver: error: --scheduler tcp://127.0.0.1:1: no Dask scheduler answered within 5 s"])


def test_a_scheduler_without_dask(tmp_path, capsys, monkeypatch):
    for name in ("dask", "dask.distributed", "distributed"):
        monkeypatch.setitem(sys.modules, name, None)        # import fails as if absent
    argv = ["sweep", DECK, "--set", f"{PEN}=5e3,2e4", "--scheduler", "tcp://127.0.0.1:8786",
            "-o", tmp_path / "s", "-q"]
    assert _error(capsys, argv) == (2, [
        "pysolver: error: --scheduler needs dask.distributed (pip install \"pysolver[dask]\")"])


def test_a_deck_that_does_not_exist(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for cmd in ("run", "check"):
        assert _error(capsys, [cmd, "nodeck.xml"]) == (2, [
            "pysolver: error: nodeck.xml: no such file"])
    assert not list(tmp_path.iterdir())


def test_an_output_folder_that_cannot_be_made(tmp_path, capsys):
    afile = tmp_path / "afile"
    afile.write_text("")
    assert _error(capsys, ["run", DECK, "-o", afile, "-q"]) == (2, [
        f"pysolver: error: -o {afile}: exists and is not a folder"])
    assert _error(capsys, ["run", DECK, "-o", afile / "sub", "-q"]) == (2, [
        f"pysolver: error: -o {afile / 'sub'}: cannot make the output folder (Not a "
        "directory)"])
    sweep = ["sweep", DECK, "--set", f"{PEN}=5e3", "-j", "0", "-o", afile, "-q"]
    status, err = _error(capsys, sweep)
    assert status == 2 and len(err) == 1 and err[0].startswith(f"pysolver: error: {afile}")


@pytest.mark.parametrize("argv, line", [
    (["--end", "abc"], "argument --end: 'abc' is not a number"),
    (["--end", "-1"], "argument --end: must be a finite number > 0, got -1"),
    (["--end", "nan"], "argument --end: must be a finite number > 0, got nan"),
    (["--end", "inf"], "argument --end: must be a finite number > 0, got inf"),
    (["--end", "1", "--steps", "2.5"], "argument --steps: '2.5' is not an integer"),
    (["--end", "1", "--steps", "0"], "argument --steps: must be an integer > 0, got 0"),
    (["--end", "1", "--dtout", "0"], "argument --dtout: must be a finite number > 0, got 0"),
    (["--steps", "4"], "--steps and --dtout need --end"),
    (["--end", "1", "--steps", "4", "--dtout", "0.1"], "give --steps or --dtout, not both"),
])
def test_bad_numbers_for_the_run(tmp_path, capsys, argv, line):
    assert _error(capsys, ["run", DECK, "-o", tmp_path / "o"] + argv) == (2, [
        f"pysolver: error: {line}"])
    assert not (tmp_path / "o").exists()


def test_argparse_usage_errors_keep_the_convention(capsys):
    assert _error(capsys, ["run"]) == (2, [
        "pysolver: error: the following arguments are required: deck"])
    assert _error(capsys, []) == (2, [
        "pysolver: error: the following arguments are required: COMMAND"])
    assert _error(capsys, ["frobnicate"]) == (2, [
        "pysolver: error: argument COMMAND: invalid choice: 'frobnicate' (choose from 'run', "
        "'check', 'convert', 'sweep')"])
    assert _error(capsys, ["check", DECK, "--bogus"]) == (2, [
        "pysolver: error: unrecognized arguments: --bogus"])


def test_a_deck_error_is_one_line(tmp_path, capsys):
    bad = tmp_path / "bad.xml"
    bad.write_text("<MotionSolve><Model><Body_Point id='2'/></Model></MotionSolve>")
    status, err = _error(capsys, ["check", bad])
    assert status == 2 and len(err) == 1
    assert err[0].startswith(f"pysolver: error: {bad}:1, Body_Point id=2, attribute 'cg_id'")


# the pipe, --version, --help -----------------------------------------------------------------

@pytest.mark.parametrize("argv", [["check", DECK],
                                  ["sweep", DECK, "--set", f"{PEN}=5e3,2e4", "-j", "0", "-o",
                                   "s", "-q"]])
def test_a_reader_that_goes_away_ends_the_command_quietly(tmp_path, argv):
    """`pysolver check deck | head -1`: the reader closes the pipe; the command exits 141
    (128 + SIGPIPE, as a Unix tool killed by it) and prints nothing on stderr."""
    env = dict(os.environ, PYTHONPATH=SRC)
    proc = subprocess.Popen([sys.executable, "-m", "pysolver", *map(str, argv)], cwd=tmp_path,
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()             # before the command writes anything
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 141 and err == ""


def test_head_reads_the_first_line(tmp_path):
    env = dict(os.environ, PYTHONPATH=SRC)
    p = subprocess.run(f"'{sys.executable}' -m pysolver check '{DECK}' | head -1; "
                       "exit ${PIPESTATUS[0]}", shell=True, executable="/bin/bash", cwd=tmp_path,
                       env=env, capture_output=True, text=True)
    assert (p.returncode, p.stdout, p.stderr) == (141, f"deck: {DECK} (xml)\n", "") or \
        (p.returncode, p.stdout, p.stderr) == (0, f"deck: {DECK} (xml)\n", "")


def test_version(tmp_path):
    p = _cli("--version", cwd=tmp_path)
    assert (p.returncode, p.stdout, p.stderr) == (0, f"pysolver {pysolver.__version__}\n", "")


def test_help_lists_every_command_on_one_line(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "100")
    with pytest.raises(SystemExit) as done:
        main(["--help"])
    assert done.value.code == 0
    lines = capsys.readouterr().out.splitlines()
    start = lines.index("  COMMAND")
    assert lines[start + 1:start + 5] == [
        "    run       run a deck: requests.csv, plot, scene.html, stats.json",
        "    check     validate a deck and list what it contains",
        "    convert   write a deck as XML, Adams .adm/.acf or msolve .py",
        "    sweep     run a parameter study of a deck (grid, sample or cases)"]


def test_one_spelling_of_the_output_folder(tmp_path, capsys):
    """-o/--output on run, convert and sweep; sweep also reads the earlier --out DIR and
    --output NAME=SPEC (now --column)."""
    import argparse

    from pysolver.cli import parser
    (commands,) = [a for a in parser()._actions if isinstance(a, argparse._SubParsersAction)]
    for cmd, meta in (("run", "DIR"), ("convert", "FILE"), ("sweep", "DIR")):
        (out,) = [a for a in commands.choices[cmd]._actions if "-o" in a.option_strings]
        assert (out.option_strings, out.dest, out.metavar) == (["-o", "--output"], "output", meta)
    new = ["sweep", DECK, "--set", f"{PEN}=5e3,2e4", "-j", "0", "-q", "--output",
           tmp_path / "new", "--column", "x_end=final:request/1/1"]
    old = ["sweep", DECK, "--set", f"{PEN}=5e3,2e4", "-j", "0", "-q", "--out",
           tmp_path / "old", "--output", "x_end=final:request/1/1"]
    assert main([str(a) for a in new]) == 0 and main([str(a) for a in old]) == 0
    capsys.readouterr()
    tables = []
    for name in ("new", "old"):
        with open(tmp_path / name / "table.csv", newline="") as fh:
            tables.append([(r[PEN], r["x_end"]) for r in csv.DictReader(fh)])
    assert tables[0] == tables[1] and len(tables[0]) == 2
    assert _error(capsys, ["sweep", DECK, "--set", f"{PEN}=5e3", "-o", "a", "-o", "b"]) == (2, [
        "pysolver: error: one output folder, not 2: a, b"])


# output folders and files ---------------------------------------------------------------------

def test_decks_of_one_stem_get_folders_of_their_own(tmp_path, capsys, monkeypatch):
    """a/deck.xml, b/deck.xml and a/deck.adm run from one folder: deck_out, deck_out-2,
    deck_out-3; a/deck.xml again writes into deck_out (its stats.json names that deck)."""
    for sub in ("a", "b"):
        (tmp_path / sub).mkdir()
        shutil.copy(DECK, tmp_path / sub / "deck.xml")
    for ext in (".adm", ".acf"):
        shutil.copy(DECKS / "forms" / "adams" / f"particle_between_lines{ext}",
                    tmp_path / "a" / f"deck{ext}")
    monkeypatch.chdir(tmp_path)
    order = ["a/deck.xml", "b/deck.xml", "a/deck.adm", "a/deck.xml"]
    for deck in order:
        assert main(["run", deck, "-q", "--no-plot", "--no-animation"]) == 0
    out = capsys.readouterr().out.splitlines()
    wrote = [line.split(", ")[0] for line in out if line.startswith("wrote ")]
    assert wrote == ["wrote deck_out/requests.csv", "wrote deck_out-2/requests.csv",
                     "wrote deck_out-3/requests.csv", "wrote deck_out/requests.csv"]
    for folder, deck in (("deck_out", "a/deck.xml"), ("deck_out-2", "b/deck.xml"),
                         ("deck_out-3", "a/deck.adm")):
        stats = json.loads((tmp_path / folder / "stats.json").read_text())
        assert stats["deck"] == str(tmp_path / deck)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a", "b", "deck_out", "deck_out-2",
                                                          "deck_out-3"]


def test_a_rerun_that_cannot_run_leaves_the_earlier_run_whole(tmp_path, capsys):
    """Review 44: a rerun whose Python routine raises (after the deck loaded) emptied the
    folder, exit 2 and the earlier run's rows gone. The earlier files are removed only once
    the new run has ended, so they stay as they were."""
    (tmp_path / "sub.py").write_text("def sfosub(id, time, par, npar, dflag, iflag):\n"
                                     "    return -par[0] * py_sysfnc('DX', [20])[0]\n")
    deck = tmp_path / "d.xml"
    deck.write_text(
        '<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>'
        '<Reference_Marker id="1" body_id="1"/><Reference_Marker id="20" body_id="2"/>'
        '<Reference_Marker id="21" body_id="1" pos_x="-1"/>'
        '<Body_Point id="2" cg_id="20" mass="1" v_ic_x="1"/>'
        '<Force_Scalar_TwoBody id="1" type="FORCE" i_marker_id="20" j_marker_id="21" '
        'usrsub_param_string="USER(10)" usrsub_fnc_name="sfosub" script_name="sub.py" '
        'interpreter="Python"/><Post_Request id="1" expr1="DX(20)"/></Model>'
        '<Simulate analysis_type="Transient" end_time="1" print_interval="0.1"/></MotionSolve>')
    out = tmp_path / "out"
    assert main(["run", str(deck), "-o", str(out), "-q", "--no-animation"]) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert sorted(before) == ["requests.csv", "requests.png", "stats.json"]
    (tmp_path / "sub.py").write_text("def sfosub(id, time, par, npar, dflag, iflag):\n"
                                     "    return -par[0] * py_sysfnc('DX', [20])[0] + typo\n")
    capsys.readouterr()
    assert main(["run", str(deck), "-o", str(out), "-q", "--no-animation"]) == 2
    assert "NameError" in capsys.readouterr().err
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


def test_a_rerun_removes_the_files_of_the_earlier_run_it_did_not_write(tmp_path, capsys):
    """Trial 44, defect 3: a second run into the folder left the first run's plot, scene,
    states and npz beside its own CSV. Now the folder holds the new run alone, the last line
    names what was removed, and files pysolver does not write stay."""
    out = tmp_path / "out1"
    assert main(["run", str(DECK), "-o", str(out), "-q", "--states", "--npz", "--end", "0.2",
                 "--steps", "4"]) == 0
    (out / "notes.txt").write_text("mine")
    (out / "requests_controller_old.csv").write_text("not a name pysolver writes")
    capsys.readouterr()
    assert main(["run", str(DECK), "-o", str(out), "-q", "--end", "0.1", "--steps", "2",
                 "--no-plot", "--no-animation"]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == (
        f"wrote {out / 'requests.csv'}, {out / 'stats.json'}; removed "
        f"{out / 'requests.png'}, {out / 'results.npz'}, {out / 'scene.html'}, "
        f"{out / 'states.csv'} (an earlier run's)")
    assert sorted(p.name for p in out.iterdir()) == [
        "notes.txt", "requests.csv", "requests_controller_old.csv", "stats.json"]
    assert (out / "requests.csv").read_text().splitlines()[-1].startswith("0.1,")
    # the same run again removes nothing: the last line is as before the change
    assert main(["run", str(DECK), "-o", str(out), "-q", "--end", "0.1", "--steps", "2",
                 "--no-plot", "--no-animation"]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == \
        f"wrote {out / 'requests.csv'}, {out / 'stats.json'}"


def test_a_loadcontrol_runs_csv_goes_with_its_run(tmp_path, capsys):
    """Another deck run into a LoadControl run's folder removes requests_controller1.csv."""
    out = tmp_path / "out"
    assert main(["run", str(DECKS / "loadcontrol_indenter.xml"), "-o", str(out), "-q",
                 "--no-plot", "--no-animation", "--end", "0.01", "--steps", "2"]) == 0
    assert (out / "requests_controller1.csv").is_file()
    capsys.readouterr()
    assert main(["run", str(DECK), "-o", str(out), "-q", "--no-plot", "--no-animation",
                 "--end", "0.01", "--steps", "2"]) == 0
    assert capsys.readouterr().out.splitlines()[-1].endswith(
        f"; removed {out / 'requests_controller1.csv'} (an earlier run's)")
    assert sorted(p.name for p in out.iterdir()) == ["requests.csv", "stats.json"]


def test_a_folder_without_a_run_keeps_files_of_those_names(tmp_path, capsys):
    """Without a stats.json naming a deck the folder holds no pysolver run: a scene.html
    there is the user's, and stays."""
    out = tmp_path / "mine"
    out.mkdir()
    (out / "scene.html").write_text("<p>my page</p>")
    assert main(["run", str(DECK), "-o", str(out), "-q", "--no-plot", "--no-animation",
                 "--end", "0.01", "--steps", "2"]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == \
        f"wrote {out / 'requests.csv'}, {out / 'stats.json'}"
    assert (out / "scene.html").read_text() == "<p>my page</p>"


def test_check_lists_the_elements_the_deck_wrote(capsys):
    """Trial 44, defect 6: a Force_SpringDamper was listed as "Force_Scalar_TwoBody -1", the
    scalar force that holds it. Spring-dampers and bushings are listed as written, with
    their numbers; a Jprim and a OneBody force by their own elements; in an Adams dataset
    each with the statement it came from (renumbered ones too)."""
    assert main(["check", str(TEST_DECKS / "springs.xml")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "Force_SpringDamper 1 (TRANSLATIONAL I=20 J=1): -k (DM(20,1) - length) - c " \
        "VR(20,1) + preload; k=100 c=0.4 length=1 preload=0" in lines
    assert "Force_SpringDamper 3 (ROTATIONAL I=40 J=41): -k (AZ(40,41) - angle) - c " \
        "WZ(40,41,41) + preload, AZ through every turn; k=3 c=0.1 angle=0.2 preload=0.4" in lines
    (vector,) = [ln for ln in lines if ln.startswith("Force_Vector_OneBody 8 ")]
    assert vector.startswith("Force_Vector_OneBody 8 (I=50 in global): (0.1*AKISPL(DX(50,42),"
                             "0,1) + 0.1*CUBSPL(DY(50),0,1,1), 0.1*QUISPL(DX(50),0,1,2) + "
                             "0.1*LINSPL(TIME,0,1), 0.01*SHF(DX(50),0.1,1.2,2,0.3,0.1) + ")
    assert vector.endswith("0.01*STEP(DZ(50),DX(50)-4,0,DX(50)+4,1), 0, 0, 0)")
    assert [ln.split(" (")[0] for ln in lines if ln.startswith("Force_")] == [
        "Force_Scalar_TwoBody 6", "Force_Scalar_TwoBody 7", "Force_SpringDamper 1",
        "Force_SpringDamper 2", "Force_SpringDamper 3", "Force_SpringDamper 4",
        "Force_Vector_OneBody 8"]
    assert main(["check", str(TEST_DECKS / "bushing.xml")]) == 0
    assert "Force_Bushing 1 (I=21 J=5, in J's axes): stiffness (2000, 3000, 2500, 40, 50, " \
        "60) damping (5, 6, 7, 0.1, 0.2, 0.3) preload (1, -2, 0.5, 0.1, -0.05, 0.02)" in \
        capsys.readouterr().out.splitlines()
    assert main(["check", str(TEST_DECKS / "all_joints.xml")]) == 0
    assert "Constraint_Jprim 99 (ATPOINT I=2401 J=2402)" in capsys.readouterr().out.splitlines()
    # the command prints each deck warning as one line on stderr
    assert main(["check", str(TEST_DECKS / "adams" / "every_statement.adm")]) == 0
    out, err = capsys.readouterr()
    assert err and all(ln.startswith("pysolver: warning: ") for ln in err.splitlines())
    lines = out.splitlines()
    for line in ("Force_SpringDamper 1 [SPRINGDAMPER/1] (TRANSLATIONAL I=301 J=105): -k "
                 "(DM(301,105) - length) - c VR(301,105) + preload; k=50 c=0.5 length=250 "
                 "preload=100",
                 "Force_Vector_TwoBody 2 [VTORQUE/1] (I=401 J=402 in 104): (0, 0, 0, 0, 0, "
                 "100*SIN(TIME))",
                 "Constraint_Jprim 5 [JPRIM/1] (INPLANE I=401 J=104)",
                 "Motion_Joint 1 [MOTION/1] (D R of joint 3): 2*TIME + 0.1*SIN(3*TIME)"):
        assert line in lines
    assert not [ln for ln in lines if " -" in ln.split(":")[0]]     # no negative ids


def test_states_and_reactions(tmp_path, capsys):
    """--states writes states.csv (time and every state) and reactions.csv (each joint's eight
    components, each motion's reaction), the numbers of the Python API; --npz results.npz."""
    deck = DECKS / "joints" / "slider_crank.xml"
    out = tmp_path / "o"
    assert main(["run", str(deck), "-o", str(out), "-q", "--no-plot", "--no-animation",
                 "--states", "--npz", "--end", "0.1", "--steps", "5"]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == "wrote " + ", ".join(
        str(out / f) for f in ("requests.csv", "states.csv", "reactions.csv", "results.npz",
                               "stats.json"))
    res = pysolver.load(deck, simulate={"analysis_type": "TRANSIENT", "end_time": 0.1,
                                        "num_step": 5}).run(progress=False)
    states = np.loadtxt(out / "states.csv", delimiter=",", skiprows=1)
    # headers with units (the deck is in m, N, s; the motion turns the crank: a torque);
    # multipliers of joint equations have the unit of their equation and stay bare; the
    # requests' AZ are tracked angles, in rad
    unit = {"x": "m", "y": "m", "z": "m", "vx": "m/s", "vy": "m/s", "vz": "m/s",
            "e0": "-", "e1": "-", "e2": "-", "e3": "-", "wx": "rad/s", "wy": "rad/s",
            "wz": "rad/s", "reaction": "N*m", "angle": "rad"}
    header = (out / "states.csv").read_text().splitlines()[0].split(",")
    assert header == ["time [s]"] + [
        f"{n} [{unit[n.split('.')[1]]}]"
        if n.startswith(("body", "motion1.reaction")) or n.endswith(".angle")
        else n for n in res.state_names]
    assert "joint1.reaction1" in header and "motion1.position_reaction" in header
    np.testing.assert_array_equal(states, np.column_stack([res.t, res.y]))
    header = (out / "reactions.csv").read_text().splitlines()[0].split(",")
    assert res.joint_ids == [1, 2, 3, 4]
    assert header == ["time [s]"] + [
        f"joint{j}.{c} [{'N' if c[0] == 'F' else 'N*m'}]" for j in (1, 2, 3, 4)
        for c in ("F", "Fx", "Fy", "Fz", "T", "Tx", "Ty", "Tz")] + ["motion1.reaction [N*m]"]
    reactions = np.loadtxt(out / "reactions.csv", delimiter=",", skiprows=1)
    np.testing.assert_array_equal(reactions, np.column_stack(
        [res.t] + [res.joint(j) for j in (1, 2, 3, 4)] + [res.motion(1)]))
    with np.load(out / "results.npz") as npz:
        np.testing.assert_array_equal(npz["joint_1"], res.joint(1))
        np.testing.assert_array_equal(npz["y"], res.y)


def test_a_deck_without_joints_writes_no_reactions(tmp_path, capsys):
    assert main(["run", str(DECK), "-o", str(tmp_path), "-q", "--no-plot", "--no-animation",
                 "--states"]) == 0
    capsys.readouterr()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["requests.csv", "states.csv",
                                                          "stats.json"]


def test_statics_in_the_summary_and_stats_json(tmp_path, capsys):
    deck = DECKS / "static_pendulum.xml"
    assert main(["run", str(deck), "-o", str(tmp_path), "-q", "--no-plot",
                 "--no-animation"]) == 0
    res = pysolver.load(deck).run(progress=False)
    (st,) = res.statics
    line = f"static at t = 0: FIM_S, {st.iterations} iterations, imbalance " \
           f"{st.imbalance:.3g}, converged"
    assert line in capsys.readouterr().out.splitlines()
    assert line in res.summary().splitlines()
    stats = json.loads((tmp_path / "stats.json").read_text())
    assert stats["statics"] == [{"time": 0.0, "method": "FIM_S", "success": True,
                                 "message": st.message, "iterations": st.iterations,
                                 "imbalance": st.imbalance, "error": st.error}]


def test_many_static_solves_are_one_line():
    import dataclasses
    res = pysolver.load(DECKS / "static_pendulum.xml").run(progress=False)
    (st,) = res.statics
    res.statics = [dataclasses.replace(st, time=float(k), imbalance=float(k), iterations=k)
                   for k in range(1, 5)]
    res.statics[2] = dataclasses.replace(res.statics[2], success=False, message="no luck")
    assert res.summary().splitlines()[-1] == (
        "static solves: 4 (FIM_S 4), 1 failed (first at t = 3: no luck), iterations up to 4, "
        "largest imbalance 4")


# imports ----------------------------------------------------------------------------------------

def test_a_c_backend_run_imports_no_scikit_sundae(tmp_path):
    """scikit-sundae (and scipy.optimize, which it loads) are imported only where they run;
    res.timing["imports"] is the time of the run's first imports, 0 on the next run."""
    code = ("import sys, pysolver\n"
            f"m = pysolver.load({str(DECK)!r})\n"
            "r1 = m.run(progress=False); r2 = m.run(progress=False)\n"
            "print(r1.meta['options']['backend'], r1.success, 'sksundae' in sys.modules,\n"
            "      'scipy.optimize' in sys.modules, r1.timing['imports'] > 0,\n"
            "      r2.timing['imports'])\n")
    p = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                       text=True, env=dict(os.environ, PYTHONPATH=SRC))
    assert p.stdout.split() == ["c", "True", "False", "False", "True", "0.0"], p.stderr[-2000:]


def test_the_scikit_sundae_backend_still_runs():
    res = pysolver.load(DECK).run(backend="sksundae", progress=False)
    assert res.success and res.meta["options"]["backend"] == "sksundae"
    assert "sksundae" in sys.modules


# units in what `pysolver run` writes ---------------------------------------------------------

def test_the_readme_deck_writes_units_once(tmp_path, capsys, monkeypatch):
    """The README deck (kg/mm/s/N): requests.csv's header carries the units and is the
    streamed one (Result.save does not write the file a second time), and stats.json maps
    each channel to its unit."""
    out = tmp_path / "out"
    calls = []
    real_save = pysolver.Result.save
    monkeypatch.setattr(pysolver.Result, "save",
                        lambda self, path: calls.append(path) or real_save(self, path))
    assert main(["run", str(DECK), "-o", str(out), "--no-animation", "--no-plot", "-q"]) == 0
    with open(out / "requests.csv", newline="") as fh:
        assert next(csv.reader(fh)) == ["time [s]", "x [mm]", "z [mm]", "force_L1 [N]",
                                        "force_L2 [N]"]
    assert calls == []
    stats = json.loads((out / "stats.json").read_text())
    assert stats["units"] == {"time": "s", "x": "mm", "z": "mm", "force_L1": "N",
                              "force_L2": "N"}
    assert "controller_units" not in stats


def test_loadcontrol_units_in_stats_json(tmp_path, capsys):
    """A LoadControl deck's stats.json gives its per-update fields' units too."""
    out = tmp_path / "out"
    assert main(["run", str(DECKS / "loadcontrol_indenter.xml"), "-o", str(out),
                 "--no-animation", "--no-plot", "-q"]) == 0
    stats = json.loads((out / "stats.json").read_text())
    assert stats["units"]["z"] == "mm" and stats["units"]["floor_force"] == "N"
    units = stats["controller_units"]
    assert (units["time"], units["target"], units["displacement"], units["velocity"],
            units["A"], units["clamped"]) == ("s", "N", "mm", "mm/s", "N/mm", None)


def test_a_sweep_says_why_cases_did_not_run(tmp_path, capsys):
    """Cases that end in `error` are rows of the table and, the first three, lines on
    standard error with their reason; the exit status is 1."""
    status = main(["sweep", str(DECK), "--set", "mass=1,2", "-o", str(tmp_path / "s"), "-q"])
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 1
    assert len(err) == 2 and all(line.startswith(f"pysolver: case {k} error: mass: sweep "
                                                 "parameter 'mass': unknown element")
                                 for k, line in enumerate(err))


@pytest.mark.parametrize("argv, start", [
    (["--column", "foo=bar"], "pysolver: error: --column 'foo': 'bar' must be"),
    (["--keep", "foo"], "pysolver: error: --keep: unknown status 'foo'")])
def test_sweep_errors_name_the_option_typed(tmp_path, capsys, argv, start):
    status, err = _error(capsys, ["sweep", DECK, "--set", f"{PEN}=1e4", "-o", tmp_path / "s",
                                  "-q", *argv])
    assert status == 2 and len(err) == 1 and err[0].startswith(start), err
