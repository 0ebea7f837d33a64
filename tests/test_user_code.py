"""User code that misbehaves, and a way to refuse it (issue 22, items 16-18): a deck or routine
calling sys.exit is a DeckError or a failed run; ``user_code=False`` / ``--no-user-code``
refuses a deck's code; ``pysolver run`` streams rows to the CSV so that a crashing C routine
loses none of them."""
import json
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

import pysolver

from helpers import DECKS

BEAD = (DECKS / "catenary_bead.xml").read_text()
PY_DECK = (DECKS / "catenary_bead.py").read_text()


def _env():
    return dict(os.environ, PYTHONPATH=str(pathlib.Path(pysolver.__file__).parents[1]))


def _cli(args, cwd):
    return subprocess.run([sys.executable, "-m", "pysolver.cli", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, env=_env())


def _bead_with(attrs):
    """Seed example 1 with its Force_Penalty as a user subroutine given by `attrs`."""
    old = 'type="EXPRESSION"\n                   expr="dy(9) - cosh(dx(9))"'
    assert old in BEAD
    return BEAD.replace(old, f'type="USERSUB" {attrs}')


# item 16: sys.exit ------------------------------------------------------------------------
def test_a_deck_script_calling_sys_exit_is_a_deck_error(tmp_path):
    """`pysolver run` exited 0 having written nothing, and check passed."""
    deck = tmp_path / "quits.py"
    deck.write_text(PY_DECK + "\nimport sys\nsys.exit(0)\n")
    line = len(PY_DECK.splitlines()) + 3
    with pytest.raises(pysolver.DeckError, match=r"the deck called sys.exit\(0\); a deck script "
                       r"is read for its statements and must not exit") as info:
        pysolver.load(deck)
    assert info.value.line == line
    for args in (["run", deck, "-o", tmp_path / "out", "--no-plot"], ["check", deck]):
        out = _cli(args, tmp_path)
        assert out.returncode == 2, (args, out.stderr)
        assert out.stderr.startswith(f"pysolver: error: {deck}:{line}")
        assert "Traceback" not in out.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("script, match", [
    # in a traced routine: it escaped model.run() as SystemExit
    ("import sys\n\n\ndef PFOSUB(id, time, par, npar, dflag, iflag):\n    sys.exit(4)\n",
     r"PFOSUB raised SystemExit: 4 \(line 5\)"),
    # at the script's top level, run at the first compile
    ("import sys\nsys.exit(3)\n\n\ndef PFOSUB(id, time, par, npar, dflag, iflag):\n"
     "    return 0.0\n", r"failed to run: SystemExit: 3 \(line 2\)"),
])
def test_sys_exit_in_a_routines_script_is_a_deck_error(tmp_path, script, match):
    (tmp_path / "bead.py").write_text(script)
    model = pysolver.loads(_bead_with(f'script_name="{tmp_path / "bead.py"}" '
                                      'usrsub_param_string="USER(9)"'))
    with pytest.raises(pysolver.DeckError, match=match):
        model.run()


def test_sys_exit_in_a_routine_called_from_the_kernel_is_a_failed_run(tmp_path):
    """A routine that cannot be traced (it converts a measure to float) runs from the kernel;
    its sys.exit at t > 0.5 ends the run with status -400 and the rows so far."""
    script = tmp_path / "bead.py"
    script.write_text(
        "import math\nimport sys\n\n\ndef PFOSUB(id, time, par, npar, dflag, iflag):\n"
        "    [x, e] = py_sysfnc('DX', [9])\n    [y, e] = py_sysfnc('DY', [9])\n"
        "    if float(time) > 0.5:\n        sys.exit(4)\n"
        "    return float(y) - math.cosh(float(x))\n")
    res = pysolver.loads(_bead_with(f'script_name="{script}" usrsub_param_string="USER(9)"')) \
        .run()
    assert not res.success and res.status == -400
    assert "PFOSUB raised SystemExit: 4" in res.message
    assert 0.45 < res.t[-1] <= 0.5


# item 17: refusing a deck's code ----------------------------------------------------------------
def test_user_code_false_refuses_a_python_deck(tmp_path):
    deck = tmp_path / "bead.py"
    deck.write_text(PY_DECK + "\nraise RuntimeError('this must never run')\n")
    with pytest.raises(pysolver.DeckError, match="a Python deck is a program, and "
                       r"user_code=False refuses code \(--no-user-code\)"):
        pysolver.load(deck, user_code=False)
    out = _cli(["check", "--no-user-code", deck], tmp_path)
    assert out.returncode == 2 and "refuses code" in out.stderr and "never run" not in out.stderr


def test_user_code_false_refuses_a_routine_before_anything_runs(tmp_path):
    """The script would write a file when run; with user_code=False load, check and run refuse
    the element, naming it, and the file never appears."""
    marker = tmp_path / "ran"
    script = tmp_path / "bead.py"
    script.write_text(f"open({str(marker)!r}, 'w').write('ran')\n\n\n"
                      "def PFOSUB(id, time, par, npar, dflag, iflag):\n    return 0.0\n")
    deck = tmp_path / "bead.xml"
    deck.write_text(_bead_with(f'script_name="{script}" usrsub_param_string="USER(9)"'))
    with pytest.raises(pysolver.DeckError, match="user_code=False refuses it") as info:
        pysolver.load(deck, user_code=False)
    assert info.value.element == "Force_Penalty" and info.value.attribute == "script_name"
    for cmd in ("check", "run"):
        out = _cli([cmd, "--no-user-code", deck] + (["--no-plot", "-o", tmp_path / "o"]
                                                     if cmd == "run" else []), tmp_path)
        assert out.returncode == 2 and "refuses it" in out.stderr
    assert not marker.exists()
    # the default runs it, at the first compile (check compiles)
    assert _cli(["check", deck], tmp_path).returncode == 0 and marker.exists()


def test_user_code_false_loads_a_plain_xml_deck():
    model = pysolver.load(DECKS / "catenary_bead.xml", user_code=False)
    assert model.source.user_code is False
    assert model.run().success


# item 18: a crashing C routine loses no row -------------------------------------------------
CRASH_C = r"""
#include <math.h>
#include "pysolver_usersub.h"

void PFOSUB(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int marker = (int)par[0], err;
  double x = 0.0, y = 0.0;
  c_sysfnc("DX", &marker, 1, &x, &err);
  c_sysfnc("DY", &marker, 1, &y, &err);
  if (*time > par[1]) {
    volatile int *nowhere = 0;
    *nowhere = 1;                      /* a crash, as a buggy routine would */
  }
  *value = y - cosh(x);
}
"""


def test_a_crashing_c_routine_loses_no_row_of_pysolver_run(tmp_path):
    """The C routine dereferences NULL past t = par[1] = 0.5: the process dies by SIGSEGV,
    and the CSV holds every row made before it (every 0.01 up to the last step IDA completed
    before trying one past 0.5), each equal to the run in process of the same routine that
    does not crash (par[1] = 1e9)."""
    (tmp_path / "crash.c").write_text(CRASH_C)
    cc = shutil.which(os.environ.get("CC", "cc")) or shutil.which("gcc")
    subprocess.run([cc, "-shared", "-fPIC", f"-I{pysolver.get_include()}",
                    str(tmp_path / "crash.c"), "-o", str(tmp_path / "crash.so"), "-lm"],
                   check=True)
    lib = tmp_path / "crash.so"
    text = _bead_with(f'usrsub_dll_name="{lib}" usrsub_param_string="USER(9, 0.5)"')
    deck = tmp_path / "crash.xml"
    deck.write_text(text)
    out = _cli(["run", deck, "-o", tmp_path / "out", "--no-plot", "-q"], tmp_path)
    assert out.returncode < 0, out.stderr[-2000:]          # killed by a signal
    lines = (tmp_path / "out" / "requests.csv").read_text().splitlines()
    assert lines[0] == "time [s],x [m],y [m],vx [m/s],vy [m/s],g,penalty_force [N]"
    rows = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])
    assert np.allclose(rows[:, 0], 0.01 * np.arange(len(rows)))
    assert rows[-1, 0] >= 0.45                 # IDA's last steps before 0.5 are about 0.02
    ref = pysolver.loads(text.replace("USER(9, 0.5)", "USER(9, 1e9)")).run()   # no crash
    assert ref.success
    np.testing.assert_array_equal(rows, ref.columns()[1][:len(rows)])


def test_stream_equals_the_saved_csv(tmp_path):
    """Model.run(stream=...) writes the rows as Result.save does, on every kind of run: the fast
    path, sensors with restarts and a changing interval, zero-crossing restore-and-shrink,
    LoadControl restarts, statics, both integrators."""
    for name in ("particle_between_lines.xml", "sensor_output_interval.xml",
                 "contact_onset_zero_crossing.xml", "loadcontrol_indenter.xml",
                 "quasi_static_stack.xml", "sensor_halt_acceleration.xml"):
        model = pysolver.load(DECKS / name)
        for backend in ("c", "sksundae"):
            res = model.run(stream=tmp_path / "s.csv", backend=backend)
            res.save(tmp_path / "full.csv")
            assert (tmp_path / "s.csv").read_bytes() == (tmp_path / "full.csv").read_bytes(), \
                (name, backend)


def test_pysolver_run_writes_the_same_csv_as_before(tmp_path):
    out = _cli(["run", DECKS / "particle_between_lines.xml", "-o", tmp_path / "o", "--no-plot",
                "-q"], tmp_path)
    assert out.returncode == 0, out.stderr
    res = pysolver.load(DECKS / "particle_between_lines.xml").run()
    res.save(tmp_path / "ref.csv")
    assert (tmp_path / "o" / "requests.csv").read_bytes() == (tmp_path / "ref.csv").read_bytes()
    assert json.loads((tmp_path / "o" / "stats.json").read_text())["success"]
