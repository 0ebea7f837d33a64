"""Syntax of Altair's own MotionSolve XML examples (trial 45): Force_Scalar_TwoBody's
body1_id/body2_id, Motion_Joint's joint_type, the degree suffix 180D, Simulate's num_steps,
start_time and print_increment, FITSPL refused with advice, FIM_D statics' log line."""
import re

import numpy as np
import pytest

import pysolver
from pysolver import DeckError
from pysolver.errors import DeckWarning

PENDULUM = """<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="2" body_id="1"/>
<Reference_Marker id="20" body_id="2" pos_x="1"/>
<Reference_Marker id="21" body_id="2"/>
<Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="0.01" inertia_yy="0.01" inertia_zz="0.01"/>
<Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="2"/>
{element}
<Post_Request id="1" expr1="AZ(21,2)" expr2="WZ(21)"/>
<Param_Transient integr_tol="1e-10"/>
</Model>{commands}</MotionSolve>"""
TRANSIENT = '<Simulate analysis_type="Transient" end_time="0.5" print_interval="0.1"/>'


def pendulum(element, commands=TRANSIENT):
    return PENDULUM.format(element=element, commands=commands)


def test_sforce_body_ids_as_in_altairs_examples():
    """Altair's DM, CUBSPL and FITSPL pages write body1_id and body2_id on
    Force_Scalar_TwoBody: they are checked against the markers' bodies, and the run is the
    one without them: a torque 2 on I = 1.01 turns the pendulum by t^2/1.01."""
    torque = ('<Force_Scalar_TwoBody id="1" type="Torque" i_marker_id="21" {b1} '
              'j_marker_id="2" {b2} val_expression="2"/>')
    with_ids = pysolver.loads(pendulum(torque.format(b1='body1_id="2"', b2='body2_id="1"')))
    plain = pysolver.loads(pendulum(torque.format(b1="", b2="")))
    a, b = with_ids.run(), plain.run()
    assert a.success and np.array_equal(a.request(1)[:, :2], b.request(1)[:, :2])
    np.testing.assert_allclose(a.request(1)[:, 0], a.t ** 2 / 1.01, rtol=0, atol=1e-9)


@pytest.mark.parametrize("b1, b2, attribute, words", [
    ('body1_id="1"', "", "body1_id", "got 1, but i_marker_id 21 is on body 2"),
    ("", 'body2_id="2"', "body2_id", "got 2, but j_marker_id 2 is on body 1"),
])
def test_sforce_body_ids_that_disagree_are_a_deck_error(b1, b2, attribute, words):
    text = pendulum(f'<Force_Scalar_TwoBody id="1" type="Torque" i_marker_id="21" {b1} '
                    f'j_marker_id="2" {b2} val_expression="2"/>')
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(text)
    assert err.value.attribute == attribute
    assert err.value.element == "Force_Scalar_TwoBody"


# Altair's TIME and TM pages: <Motion_Joint ... expr="STEP5(TIME,.2,0,.4,180D)" joint_type="R"/>
TM_EXAMPLE = ('<Motion_Joint id="1" type="EXPRESSION" val_type="D" '
              'expr="STEP5(TIME,.2,0,.4,{angle})" joint_id="1" {kind}/>')


@pytest.mark.parametrize("kind", ['joint_type="R"', 'motion_type="R"', ""])
def test_altairs_motion_joint_example_runs(kind):
    """The example as Altair writes it (joint_type, the degree suffix 180D) turns the
    pendulum by STEP5(t, 0.2, 0, 0.4, pi) exactly as motion_type and PI do."""
    res = pysolver.loads(pendulum(TM_EXAMPLE.format(angle="180D", kind=kind))).run()
    ref = pysolver.loads(pendulum(TM_EXAMPLE.format(angle="PI", kind='motion_type="R"'))).run()
    assert res.success, res.message
    np.testing.assert_array_equal(res.request(1)[:, :2], ref.request(1)[:, :2])
    assert res.request(1)[-1, 0] == pytest.approx(np.pi, abs=1e-9)
    assert pysolver.loads(pendulum(TM_EXAMPLE.format(angle="180D", kind=kind))) \
        .motions[1].expr == ("call", "STEP5", [("name", "TIME", 6), ("num", 0.2), ("num", 0.0),
                                               ("num", 0.4), ("num", np.pi)], 0)


def test_joint_type_and_motion_type_together_are_a_deck_error():
    text = pendulum(TM_EXAMPLE.format(angle="180D", kind='motion_type="R" joint_type="R"'))
    with pytest.raises(DeckError, match=r"give motion_type or joint_type, not both \(the same "
                                        r"attribute\)") as err:
        pysolver.loads(text)
    assert err.value.attribute == "joint_type"


def test_a_bad_joint_type_is_named_as_written():
    text = pendulum(TM_EXAMPLE.format(angle="180D", kind='Joint_Type="X"'))
    with pytest.raises(DeckError, match="got 'X'; expected one of R, T") as err:
        pysolver.loads(text)
    assert err.value.attribute == "Joint_Type"


@pytest.mark.parametrize("text, value", [
    ("180D", np.pi), ("90d", np.pi / 2), ("2.D", np.radians(2.0)), (".5D", np.radians(0.5)),
    ("1.5E-1D", np.radians(0.15)), ("30D+10D", np.radians(30) + np.radians(10)),
    ("(2.5D)-1", np.radians(2.5) - 1), ("2.5D - 1", np.radians(2.5) - 1),
    # Fortran D exponents keep their meaning: digits after the D, then no letter, digit, point
    ("1D0", 1.0), ("1d0", 1.0), ("1D-3", 1e-3), ("1.0D+3", 1e3), ("5D2", 500.0),
    ("30D+10", 30e10), ("2D3*2", 4000.0),
])
def test_the_degree_suffix_and_d_exponents(text, value):
    """Adams' rule (docs/adams.md "Numbers") in every deck's expressions: a D after a number
    and before no letter, digit or parenthesis is degrees; only expressions that were errors
    (a name D after a number) change meaning."""
    from pysolver.deck import expr as ex
    assert _value(ex.parse(text)) == pytest.approx(value, rel=1e-15, abs=0)


def _value(tree):
    """The number a tree of numbers, signs and + - * / is."""
    if tree[0] == "num":
        return tree[1]
    if tree[0] == "neg":
        return -_value(tree[1])
    a, b = _value(tree[2]), _value(tree[3])
    return {"+": a + b, "-": a - b, "*": a * b, "/": a / b}[tree[1]]


@pytest.mark.parametrize("text, words", [
    ("1D2D", "unexpected 'D2D' after the end of the expression"),
    ("2DX(1)", "unexpected 'DX' after the end of the expression"),
    ("180DTOR", "unexpected 'DTOR' after the end of the expression"),
    ("2D(1)", "unexpected 'D' after the end of the expression"),
])
def test_what_is_no_degree_suffix_stays_an_error(text, words):
    from pysolver.deck import expr as ex
    from pysolver.errors import ExpressionError
    with pytest.raises(ExpressionError, match=words):
        ex.parse(text)


def test_num_steps_is_num_step():
    """Altair's Simulate page writes num_step in its format box and num_steps in its text."""
    cmd = '<Simulate analysis_type="Transient" end_time="0.5" {}="5"/>'
    a = pysolver.loads(pendulum("", cmd.format("num_steps"))).run()
    b = pysolver.loads(pendulum("", cmd.format("num_step"))).run()
    np.testing.assert_allclose(a.t, [0, 0.1, 0.2, 0.3, 0.4, 0.5], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(a.t, b.t)
    with pytest.raises(DeckError, match="give num_step or num_steps, not both"):
        pysolver.loads(pendulum("", '<Simulate analysis_type="Transient" end_time="0.5" '
                                    'num_step="5" num_steps="5"/>'))


@pytest.mark.parametrize("commands, attribute, words", [
    ('<Simulate analysis_type="Transient" start_time="1" end_time="2" print_interval="0.25"/>',
     "start_time", re.escape("got 1; a run starts at TIME = 0 (pysolver has no other start "
                             "time): leave start_time out or give 0")),
    ('<Simulate analysis_type="Static" start_time="1"/>', "start_time",
     "got 1; a run starts at TIME = 0"),
    ('<Simulate analysis_type="Transient" end_time="1" num_step="4"/>'
     '<Simulate analysis_type="Transient" start_time="2" end_time="3" num_step="4"/>',
     "start_time", "start_time must equal the time the previous command ended \\(1\\)"),
])
def test_start_time_is_where_the_run_is(commands, attribute, words):
    """A run starts at TIME = 0 (decision, docs/deck-language.md's Simulate row): start_time
    is accepted where the run already is, a DeckError elsewhere."""
    with pytest.raises(DeckError) as err:
        pysolver.loads(pendulum("", commands))
    assert re.search(words, str(err.value)), str(err.value)
    assert err.value.attribute == attribute and err.value.element == "Simulate"


def test_start_time_where_the_run_is_is_accepted():
    text = pendulum("", '<Simulate analysis_type="Transient" start_time="0" end_time="1" '
                        'num_step="2"/><Simulate analysis_type="Transient" start_time="1" '
                        'end_time="2" num_step="2"/>')
    np.testing.assert_array_equal(pysolver.loads(text).run().t, [0, 0.5, 1, 1.5, 2])


def test_print_increment_draws_a_deck_warning_at_its_line():
    """Altair: print_increment is the output frequency in integrator steps; pysolver prints at
    fixed times, so the value is not used: a DeckWarning at its line, and the command prints
    100 intervals."""
    text = pendulum("", '<Simulate analysis_type="Transient" end_time="1"\n'
                        '  print_increment="5"/>')
    with pytest.warns(DeckWarning) as record:
        model = pysolver.loads(text)
    (w,) = [r.message for r in record if isinstance(r.message, DeckWarning)]
    assert str(w).endswith("print_increment = 5 is not used: pysolver prints at fixed times, "
                           "never every n integrator steps; this command prints every 0.01 "
                           "(100 intervals; give print_interval or num_step)")
    # lxml's line of an element: where its start tag ends, here print_increment's own line
    assert w.line == next(k for k, line in enumerate(text.splitlines(), 1)
                          if "print_increment" in line)
    assert w.attribute == "print_increment"
    assert len(model.run().t) == 101


def test_fitspl_is_refused_with_advice():
    text = pendulum('<Reference_Spline id="7">0 0\n1 1\n2 4\n3 9</Reference_Spline>'
                    '<Post_Request id="2" expr1="FITSPL(TIME,0,7)"/>')
    with pytest.raises(DeckError) as err:
        pysolver.loads(text)
    assert str(err.value).endswith(
        "bad expression 'FITSPL(TIME,0,7)': FITSPL is not supported: MotionSolve's pages do "
        "not say which FITPACK B-spline fit it is (its degree '3rd order' and 'of the 2nd "
        "degree' on one page; its knots and smoothing not at all); use CUBSPL or AKISPL of "
        "the same Reference_Spline (at column 1)")
    assert err.value.attribute == "expr1"


def test_a_fim_d_static_says_it_is_solved_by_fim_s():
    """docs/statics.md: a pure static solve with FIM_D is FIM_S; res.log says so."""
    text = pendulum('<Force_Gravity grav_y="-9.81"/><Param_Static method="FIM_D"/>'
                    '<Force_SpringDamper id="1" type="ROTATIONAL" i_marker_id="21" '
                    'j_marker_id="2" stiffness="20"/>', '<Simulate analysis_type="Static"/>')
    res = pysolver.loads(text).run()
    assert res.success and res.statics[0].method == "FIM_S"
    assert ("Param_Static method FIM_D: the Static command at t = 0 is solved by FIM_S (FIM_D "
            "follows quasi-static paths; docs/statics.md)") in res.log
    plain = pysolver.loads(text.replace("FIM_D", "FIM_S")).run()
    assert not any("FIM_D" in line for line in plain.log)


@pytest.mark.parametrize("ext", [".xml", ".adm", ".py"])
def test_altairs_syntax_converts_to_every_form(tmp_path, ext):
    """joint_type, 180D, body1_id/body2_id and num_steps convert (pysolver convert) to XML
    (written motion_type and num_step), an Adams dataset and msolve classes, each running as
    the deck does, to the bit."""
    from pysolver.convert import convert
    deck = tmp_path / "tm.xml"
    deck.write_text(pendulum(
        TM_EXAMPLE.format(angle="180D", kind='joint_type="R"')
        + '<Force_Scalar_TwoBody id="1" type="Torque" i_marker_id="21" body1_id="2" '
          'j_marker_id="2" body2_id="1" val_expression="0.1*STEP(TIME,0,0,1,90D)"/>',
        '<Simulate analysis_type="Transient" end_time="0.5" num_steps="5"/>'))
    ref = pysolver.load(deck).run()
    out = tmp_path / f"out{ext}"
    convert(deck, out)
    res = pysolver.load(out).run()
    assert res.success and len(res.t) == 6
    np.testing.assert_array_equal(res.request(1)[:, :2], ref.request(1)[:, :2])
    if ext == ".xml":
        assert 'motion_type="R"' in out.read_text() and 'num_step="5"' in out.read_text()
