"""Param_Transient's step settings (trial 44, defects 6 and 7): h_min above h_max is one error
naming both, wherever the pair is given; an IDA failure with h_min set says so; static and
quasi-static commands take integr_tol alone, and a run or a sweep that sets the other settings
for them is told."""
import re

import pytest

import pysolver

from helpers import DECKS

LINES = DECKS / "particle_between_lines.xml"
STACK = DECKS / "quasi_static_stack.xml"
PAIR = "h_min (0.001) > h_max (0.0001): the smallest step IDA may take is larger than the largest"


def test_h_min_above_h_max_is_one_error_naming_both():
    """As run options, in the deck's Param_Transient, as a sweep case (its row, and
    run(params=)), and a case's h_min against the deck's h_max."""
    model = pysolver.load(LINES)
    with pytest.raises(ValueError) as err:
        model.run(h_min=1e-3, h_max=1e-4)
    assert str(err.value) == PAIR
    text = re.sub(r"<Param_Transient[^>]*/>",
                  '<Param_Transient integr_tol="1e-6" h_min="1e-3" h_max="1e-4"/>',
                  LINES.read_text())
    with pytest.raises(pysolver.DeckError) as err:
        pysolver.loads(text)
    assert (err.value.reason, err.value.element, err.value.attribute) == \
        (PAIR, "Param_Transient", "h_min")
    case = {"Param_Transient/h_min": 1e-3, "Param_Transient/h_max": 1e-4}
    sw = pysolver.sweep(LINES, [case], processes=0)
    assert (sw.rows[0]["status"], sw.rows[0]["message"]) == (
        "error", f"Param_Transient, attribute 'h_min': sweep parameter "
                 f"'Param_Transient/h_min': {PAIR}")
    with pytest.raises(pysolver.DeckError, match=re.escape(PAIR)):
        model.run(params=case)
    bounded = pysolver.loads(LINES.read_text().replace(
        '<Param_Transient', '<Param_Transient h_max="1e-4"'))
    with pytest.raises(pysolver.DeckError, match=re.escape(PAIR)):
        bounded.run(params={"Param_Transient/h_min": 1e-3})
    assert model.run().success                       # the deck's own settings again


def test_an_ida_failure_with_h_min_set_names_it():
    res = pysolver.load(LINES).run(h_min=0.1)
    assert not res.success
    assert res.message == ("IDA failed at t = 0: Convergence test failures occurred too many "
                           "times. (h_min = 0.1 is set: IDA may take no smaller step; a smaller "
                           "h_min, or 0, lets it)")


def test_quasi_statics_take_the_tolerance_alone_and_say_so():
    """On decks/quasi_static_stack.xml (FIM_D, no transient): max_num_steps and h_max change
    nothing (25 steps, the same path) and the run's log says they are not used; the tolerance
    acts; a sweep varying them warns."""
    model = pysolver.load(STACK)
    plain = model.run()
    assert plain.success and not [line for line in plain.log if "Param_Transient" in line]
    for options, names, verb in ((dict(max_num_steps=5), "max_num_steps", "is"),
                                 (dict(h_max=1e-6, h_min=1e-9), "h_max, h_min", "are"),
                                 (dict(params={"Param_Transient/max_num_steps": 3}),
                                  "max_num_steps", "is")):
        res = model.run(**options)
        assert res.success and res.stats["steps"] == plain.stats["steps"]
        assert (res.y == plain.y).all()
        assert f"Param_Transient {names} {verb} not used: static and quasi-static commands " \
               "(FIM_S, MKEAM, FIM_D) take integr_tol alone, and the run has no transient " \
               "command (docs/statics.md)" in res.log
    assert model.run(integr_tol=1e-10).stats["steps"] > plain.stats["steps"]
    with pytest.warns(UserWarning) as got:
        pysolver.sweep(model, [{"Param_Transient/max_num_steps": 3,
                                "Param_Transient/integr_tol": 1e-6}], processes=0)
    assert [str(w.message) for w in got] == [
        "Param_Transient/max_num_steps: the deck has no transient command, and its static and "
        "quasi-static commands take integr_tol alone (docs/statics.md): these values change "
        "nothing"]


def test_a_deck_with_a_transient_too_is_told_which_commands_take_them():
    text = STACK.read_text().replace(
        '<Simulate analysis_type="Quasi-Static" end_time="1" print_interval="0.01"/>',
        '<Simulate analysis_type="Quasi-Static" end_time="1" print_interval="0.01"/>\n  '
        '<Simulate analysis_type="Transient" end_time="1.1" print_interval="0.01"/>')
    res = pysolver.loads(text).run(max_num_steps=100000)
    assert res.success
    assert "Param_Transient max_num_steps acts on the transient commands only: static and " \
           "quasi-static commands (FIM_S, MKEAM, FIM_D) take integr_tol alone " \
           "(docs/statics.md)" in res.log
