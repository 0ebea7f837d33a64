"""Errors a user subroutine reports (py_errmes, c_errmes, a raise, sys.exit): on a branch of the
state the run fails only if and when the state takes it (status -400, the routine's message and
the time of the failing call); on no branch a traced routine is refused when the model is first
compiled; and the -400 message tells the failing call's time from the run's last converged step.
"""
import re

import numpy as np
import pytest

import pysolver
from pysolver.solve import fast

from helpers import DECKS
from scenes import usersub_library

HEAD = ("import math\nimport sys\n\n\ndef PFOSUB(id, time, par, npar, dflag, iflag):\n"
        "    [x, e] = py_sysfnc('DX', [int(par[0])])\n"
        "    [y, e] = py_sysfnc('DY', [int(par[0])])\n")
TAIL = "    return y - math.cosh(x)\n"
ERRMES = "py_errmes(1, 'x went negative', id, '{endflag}')"
RAISE = "raise ValueError('x went negative')"

#: The -400 message of a call at a time past the run's last converged step.
PAST = re.compile(r"user subroutine \(id 1\): (.*) \(called at t = (\S+); "
                  r"the run's last converged step: t = (\S+)\)")


def routine(condition, action):
    """The bead's g = y - cosh(x) (seed example 1) with `action` on the branch `condition`
    (None: on no branch)."""
    if condition is None:
        return HEAD + f"    {action}\n" + TAIL
    return HEAD + f"    if {condition}:\n        {action}\n" + TAIL


def bead_xml(attrs):
    text = (DECKS / "catenary_bead.xml").read_text()
    old = 'type="EXPRESSION"\n                   expr="dy(9) - cosh(dx(9))"'
    assert old in text
    return text.replace(old, f'type="USERSUB" {attrs}')


def bead_model(tmp_path, source, form="xml"):
    """Seed example 1 with its penalty's g from the routine `source`: an XML deck with the
    script (xml), a Python deck with the function in it (function) or with the script
    (script)."""
    script = tmp_path / "bead_sub.py"
    script.write_text(source)
    if form == "xml":
        return pysolver.loads(bead_xml(f'script_name="{script}" usrsub_param_string="USER(9)"'))
    deck = (DECKS / "catenary_bead.py").read_text()
    old = 'PFORCE(1, LABEL="Particle sliding on a catenary", FUNCTION="DY(9)-COSH(DX(9))",'
    assert old in deck
    if form == "function":
        new = source + 'PFORCE(1, FUNCTION="USER(9)", ROUTINE=PFOSUB,'
    else:
        new = f'PFORCE(1, FUNCTION="USER(9)", ROUTINE="PFOSUB", SCRIPT={str(script)!r},'
    return pysolver.loads(deck.replace(old, new), fmt="py")


def failed_past(res, text):
    """(time of the failing call, the run's last converged step) of a run that ended in the
    routine's error `text` at a trial time past its last converged step."""
    assert not res.success and res.status == -400
    match = PAST.fullmatch(res.message)
    assert match is not None, res.message
    assert match[1] == text
    called, last = float(match[2]), float(match[3])
    assert called > last and res.t[-1] <= last
    return called, last


@pytest.mark.parametrize("form", ["xml", "function", "script"])
@pytest.mark.parametrize("endflag", ["STOP", "WARNING"])
def test_py_errmes_on_a_branch_of_x_fails_the_run_where_the_state_takes_it(tmp_path, form,
                                                                           endflag):
    """The bead slides from x = 0.5 through x = 0 at t ~ 0.51: py_errmes on `x < 0` (any
    endflag) loads and runs, and fails the run there as `raise` on that branch does: the same
    rows, the routine and its message, the same times. Before, the deck was refused (exit 2,
    "PFOSUB: x went negative (id 1) (line 9)") though x never went negative."""
    model = bead_model(tmp_path, routine("x < 0", ERRMES.format(endflag=endflag)), form)
    res = model.run()
    called, last = failed_past(res, "PFOSUB: x went negative (id 1)")
    assert 0.5 < last < called < 0.55
    assert np.all(res.request(1)[:, 0] >= 0.0)
    # the line of the call: in the script, or in the deck the function is defined in
    line = 9 if form != "function" else 9 + (DECKS / "catenary_bead.py").read_text() \
        .splitlines().index("PFORCE(1, LABEL=\"Particle sliding on a catenary\", "
                            "FUNCTION=\"DY(9)-COSH(DX(9))\",")
    (path,) = res.meta["usersubs"].values()
    assert ("Python callback (not traced: the branch DX(9) < 0 reports an error with py_errmes: "
            f"x went negative (id 1) (line {line})), called from the kernel") in path
    raised = bead_model(tmp_path / "..", routine("x < 0", RAISE), form).run()
    assert failed_past(raised, "PFOSUB raised ValueError: x went negative") == (called, last)
    np.testing.assert_array_equal(raised.t, res.t)
    np.testing.assert_array_equal(raised.y, res.y)


def test_py_errmes_on_a_branch_of_time_fails_the_run_past_it(tmp_path):
    """`if time > 0.5:` is a branch too: the call past 0.5 fails, the rows end before it."""
    res = bead_model(tmp_path, routine("time > 0.5", ERRMES.format(endflag="STOP"))).run()
    called, last = failed_past(res, "PFOSUB: x went negative (id 1)")
    assert last <= 0.5 < called and res.t[-1] <= 0.5


def test_a_branch_the_state_never_takes_never_fails(tmp_path):
    """py_errmes on `x < -10`: called from the kernel, the run ends cleanly, as the expression's
    (within the differenced routine's error: 5e-8 at integr_tol 1e-10)."""
    ref = pysolver.load(DECKS / "catenary_bead.xml").run(integr_tol=1e-10)
    res = bead_model(tmp_path, routine("x < -10", ERRMES.format(endflag="STOP"))) \
        .run(integr_tol=1e-10)
    assert res.success, res.message
    assert "not traced: the branch (DX(9) - -10) < 0 reports an error" in \
        next(iter(res.meta["usersubs"].values()))
    np.testing.assert_array_equal(res.t, ref.t)
    np.testing.assert_allclose(res.request(1)[:, :4], ref.request(1)[:, :4], atol=1e-6)


@pytest.mark.parametrize("action, text", [
    (ERRMES.format(endflag="STOP"), "PFOSUB: x went negative (id 1)"),
    (RAISE, "PFOSUB raised ValueError: x went negative"),
    ("sys.exit(4)", "PFOSUB raised SystemExit: 4"),
])
def test_a_branch_taken_at_the_start_fails_at_t_0(tmp_path, action, text):
    """`if x > 0:` holds at the initial state: the first call fails the run at t = 0, its
    time that of the run (so it is named once); a raise and sys.exit alike."""
    res = bead_model(tmp_path, routine("x > 0", action)).run()
    assert (res.success, res.status, res.message) == \
        (False, -400, f"user subroutine (id 1): {text} (t = 0)")


@pytest.mark.parametrize("action, match", [
    (ERRMES.format(endflag="STOP"), r"PFOSUB: x went negative \(id 1\) \(line 8\)"),
    (RAISE, r"PFOSUB raised ValueError: x went negative \(line 8\)"),
    ("sys.exit(4)", r"PFOSUB raised SystemExit: 4 \(line 8\)"),
])
def test_on_no_branch_a_traced_routine_is_refused_at_its_first_compile(tmp_path, action, match):
    """A routine that fails at every state (no branch leads to it) is a DeckError when the
    model is first compiled, naming the element, its script attribute and the line: py_errmes
    as a raise (the decision docs/user-subroutines.md states)."""
    model = bead_model(tmp_path, routine(None, action))
    with pytest.raises(pysolver.DeckError, match=match) as info:
        model.run()
    assert (info.value.element, info.value.id, info.value.attribute) == \
        ("Force_Penalty", 1, "script_name")


def test_an_error_in_the_iflag_call_says_its_values_were_0(tmp_path):
    """`x <= 0` on a branch: the routine is called from the kernel, and its iflag call, where
    time and every value read are 0, takes the branch: the DeckError says so."""
    model = bead_model(tmp_path, routine("x <= 0", ERRMES.format(endflag="STOP")))
    with pytest.raises(pysolver.DeckError) as info:
        model.run()
    assert info.value.reason == ("PFOSUB (iflag call, time and every value it reads 0): "
                                 "PFOSUB: x went negative (id 1)")


# -- the routine the deck names, and the function it called (trial 43, item 9) ---------------

def named_model(tmp_path, action, condition, name="BEAD_RAISE"):
    """The bead with the routine `name` (another, PFOSUB, fine, in the same script) doing
    `action` on `condition`."""
    source = routine(None, "pass") + "\n\n" + routine(condition, action).replace(
        "import math\nimport sys\n\n\ndef PFOSUB", f"def {name}")
    script = tmp_path / "two_subs.py"
    script.write_text(source)
    return pysolver.loads(bead_xml(f'script_name="{script}" usrsub_fnc_name="{name}" '
                                   'usrsub_param_string="USER(9)"'))


@pytest.mark.parametrize("action, text", [
    (RAISE, "BEAD_RAISE raised ValueError: x went negative"),
    (ERRMES.format(endflag="STOP"), "BEAD_RAISE: x went negative (id 1)"),
])
def test_a_failing_run_names_the_routine_the_deck_names(tmp_path, action, text):
    """usrsub_fnc_name="BEAD_RAISE" failing on `x < 0`: the -400 message named the element's
    conventional routine (PFOSUB), which the script also defines."""
    called, last = failed_past(named_model(tmp_path, action, "x < 0").run(), text)
    assert 0.5 < last < called < 0.55


@pytest.mark.parametrize("action, condition, reason", [
    (RAISE, None, "BEAD_RAISE raised ValueError: x went negative (line 15)"),
    (ERRMES.format(endflag="STOP"), None, "BEAD_RAISE: x went negative (id 1) (line 15)"),
    (ERRMES.format(endflag="STOP"), "x <= 0",
     "BEAD_RAISE (iflag call, time and every value it reads 0): BEAD_RAISE: x went negative "
     "(id 1)"),
])
def test_a_refused_routine_is_named_as_the_deck_names_it(tmp_path, action, condition, reason):
    """The DeckErrors of a routine that fails at every state, or in its iflag call."""
    with pytest.raises(pysolver.DeckError) as info:
        named_model(tmp_path, action, condition).run()
    assert info.value.reason == reason


def test_a_wrong_py_syspar_partial_names_the_routine_and_py_syspar(tmp_path):
    """A Python routine's wrong partial was reported as `c_syspar gave the partial ...`."""
    action = "py_syspar('DY', [int(par[0])], [5.0])"
    model = named_model(tmp_path, action, "float(x) > -1", name="BEAD_SYSPAR")
    res = model.run()
    assert (res.success, res.status, res.message) == (
        False, -400, "user subroutine (id 1): BEAD_SYSPAR: py_syspar gave the partial in DY(9) "
        "as 5, but differences of its value give 1 (t = 0)")


# -- the time in the message ------------------------------------------------------------------

BOOM = routine("time > 1.0", "raise RuntimeError(f'boom at time {time!r}')")
SENSOR = ('<Sensor_Event id="1" expr="DY(9)" compare="GE" value="100" halt="TRUE"/>\n'
          '  </Model>')


@pytest.mark.parametrize("sensor", [False, True])
def test_the_failing_calls_time_and_the_last_converged_step_are_told_apart(tmp_path, sensor,
                                                                            monkeypatch):
    """A routine failing past t = 1 was reported as `... boom at time 1.0036532571689383
    (t = 0.993544)`: its message's time (IDA's trial step) and the run's last converged step
    are now both named as such, the same to the bit on the batched path and the general loop
    (and on the batched path's loop for sensors)."""
    script = tmp_path / "boom.py"
    script.write_text(BOOM)
    text = bead_xml(f'script_name="{script}" usrsub_param_string="USER(9)"')
    if sensor:
        text = text.replace("</Model>", SENSOR)
    model = pysolver.loads(text)
    res = model.run(progress=False)
    from pysolver.solve.run import _settings
    batched = fast.fast_run(model.compile(), _settings(model.compile(), {})[0], ())
    assert batched is not None and batched.acting == sensor
    match = PAST.fullmatch(res.message)
    assert match is not None, res.message
    own = re.fullmatch(r"PFOSUB raised RuntimeError: boom at time (\S+)", match[1])
    assert own is not None and f"{float(own[1]):.6g}" == match[2]
    called, last = failed_past(res, match[1])
    assert last < 1.0 < called
    with monkeypatch.context() as m:
        m.setattr(fast, "ENABLED", False)
        general = model.run(progress=False)
    assert (general.success, general.status, general.message) == \
        (res.success, res.status, res.message)
    np.testing.assert_array_equal(general.t, res.t)


# -- C routines: called, never traced ---------------------------------------------------------

C_ROUTINES = r"""
#include <math.h>
#include "pysolver_usersub.h"

static double bead(double *par, double *x) {
  int marker = (int)par[0], err;
  double y;
  c_sysfnc("DX", &marker, 1, x, &err);
  c_sysfnc("DY", &marker, 1, &y, &err);
  return y - cosh(*x);
}

void NEGATIVE(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
              double *value) {
  double x;
  *value = bead(par, &x);
  if (x < 0) c_errmes(1, "x went negative", *id, "STOP");
}

void LATE(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
          double *value) {
  double x;
  *value = bead(par, &x);
  if (*time > 0.5) c_errmes(1, "too late", *id, "STOP");
}
"""


@pytest.fixture(scope="module")
def c_library(tmp_path_factory):
    lib = usersub_library(tmp_path_factory.mktemp("cerrmes"), C_ROUTINES)
    if lib is None:
        pytest.skip("no C compiler on this machine to build the test's subroutine library")
    return lib


@pytest.mark.parametrize("name, text, bounds", [
    ("NEGATIVE", "x went negative", (0.5, 0.55)),
    ("LATE", "too late", (0.45, 0.5)),
])
def test_c_errmes_on_a_branch_fails_the_run_where_the_state_takes_it(c_library, tmp_path,
                                                                      name, text, bounds):
    """A C routine is called, not traced: c_errmes on `x < 0` or `time > 0.5` loads, runs
    and fails there, as the Python routine does; the message names the routine."""
    res = pysolver.loads(bead_xml(f'usrsub_dll_name="{c_library}" usrsub_fnc_name="{name}" '
                                  'usrsub_param_string="USER(9)"')).run()
    called, last = failed_past(res, f"{name}: {text}")
    assert bounds[0] < last < called and res.t[-1] <= bounds[1]
    if name == "LATE":
        assert last <= 0.5 < called
    else:
        assert np.all(res.request(1)[:, 0] >= 0.0)
