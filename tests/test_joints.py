"""Constraint_Joint: closed forms, conservation laws, every type's equations held at every
output row, redundant equations removed, and clear errors for bad joints."""
import json
import re

import numpy as np
import pytest
from scipy.special import ellipk

import pysolver
from pysolver import DeckError

from helpers import ROOT, TEST_DECKS

JOINTS = ROOT / "decks" / "joints"
PENDULUM_W2 = 9.81 * 2 / (4 + 1e-3)     # m g L / (m L^2 + I) of decks/joints/pendulum_revolute.xml


def _with(text, **attrs):
    """The deck text with Simulate's attributes replaced."""
    for key, value in attrs.items():
        text = re.sub(rf'{key}="[^"]*"', f'{key}="{value!r}"', text)
    return text


def test_revolute_pendulum_period_is_the_elliptic_integrals():
    """Released horizontally, the pendulum is at the bottom (x = 0) at every odd quarter period
    T/4 = K(1/2) / w0 and back at the start at T: the time error there, |x| / |v|, is below
    1e-9 of the period at a tight tolerance, and the height at T/2 and T and the position at T
    within 200 x the tolerance x the 2 m length (4e-9 m; measured 3.6e-10..1.7e-9 m over
    integr_tol within 1e-4 of 1e-11, either dense solver, stop 38: rounding moves it)."""
    period = float(4 * ellipk(0.5) / np.sqrt(PENDULUM_W2))
    text = _with((JOINTS / "pendulum_revolute.xml").read_text(), end_time=period,
                 print_interval=period / 4)
    res = pysolver.loads(text).run(integr_tol=1e-11)
    assert res.success, res.message
    q = res.request(1)
    assert np.allclose(res.t, period * np.arange(5) / 4, rtol=1e-14, atol=0)
    speed = np.hypot(q[:, 2], q[:, 3])
    bottom = [1, 3]
    assert np.all(np.abs(q[bottom, 0]) / speed[bottom] < 1e-9 * period)
    assert np.abs(q[[0, 2, 4], 1]).max() < 4e-9 and np.abs(q[4, :2] - [2, 0]).max() < 4e-9
    # energy (0 at the start) within 100 x the tolerance of m g L (the global error: tens of
    # the local tolerance; 3e-10 to 6e-10 of m g L measured) and the joint's gap at every row
    assert np.abs(q[:, 5]).max() < 100 * 1e-11 * 9.81 * 2 and np.abs(q[:, 6]).max() < 1e-10


@pytest.mark.parametrize("tol", [1e-6, 1e-8])
def test_revolute_pendulum_converges_to_the_exact_solution(tol):
    """Position error against the converged reference table (benchmarks/data) below 200 x
    the tolerance x the 2 m length (measured 2.2e-4 m at 1e-6, 7.1e-7 m at 1e-8: BDF's global
    error over 2.5 swings), and the joint's gap below the tolerance."""
    ref = json.loads((ROOT / "benchmarks" / "data" / "joint_references.json").read_text())
    table = ref["problems"]["pendulum_revolute"]
    res = pysolver.load(JOINTS / "pendulum_revolute.xml").run(integr_tol=tol)
    assert res.success, res.message
    q = res.request(1)
    t = np.array(table["times"])
    rows = np.searchsorted(res.t, t)
    assert np.allclose(res.t[rows], t, atol=1e-12)
    err = np.hypot(q[rows, 0] - table["x"], q[rows, 1] - table["y"]).max()
    assert err < 200 * tol * 2
    assert np.abs(q[:, 6]).max() < 2 * tol


def test_spherical_pendulum_keeps_energy_and_vertical_angular_momentum():
    res = pysolver.load(JOINTS / "spherical_pendulum.xml").run(integr_tol=1e-9)
    assert res.success, res.message
    q = res.request(1)
    assert np.ptp(q[:, 4]) < 1e-6                    # energy, J (about 10 J swing of terms)
    assert np.abs(q[:, 5] + 1.7337828583764459).max() < 1e-6
    assert np.abs(q[:, 3] - 1.0).max() < 1e-9        # the rod's length
    assert np.abs(q[:, 6]).max() < 1e-9              # the joint's gap


SLIDE = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1" theta="{theta!r}"/>
  <Reference_Marker id="20" body_id="2" theta="{theta!r}"/>
  <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="0.1" inertia_yy="0.2" inertia_zz="0.3"/>
  <Force_Gravity grav_y="-9.81"/>
  <Constraint_Joint id="1" type="TRANSLATIONAL" i_marker_id="20" j_marker_id="1"/>
  <Post_Request id="1" expr1="DX(20)" expr2="DY(20)" expr3="DZ(20)" expr4="AX(20,1)"
    expr5="AY(20,1)" expr6="AZ(20,1)"/>
  <Param_Transient integr_tol="1e-6"/></Model>
  <Simulate analysis_type="Transient" end_time="1" print_interval="0.1"/></MotionSolve>"""


def test_a_body_slides_down_a_translational_joint_as_the_closed_form():
    """Marker z axes along (0, sin theta, cos theta) after a rotation theta about x: the body
    moves along it with the acceleration's component g sin(theta) down, and does not turn:
    within 10 x the tolerance of the 2.2 m travelled at integr_tol 1e-9 (the first steps of
    so tight a tolerance once failed the corrector: csrc/ida.c, weights)."""
    theta = 0.7
    res = pysolver.loads(SLIDE.format(theta=theta)).run(integr_tol=1e-9)
    assert res.success, res.message
    q = res.request(1)
    axis = np.array([0.0, -np.sin(theta), np.cos(theta)])
    s = -9.81 * axis[1] * res.t ** 2 / 2            # travel along the axis
    np.testing.assert_allclose(q[:, :3], np.outer(s, axis), rtol=0, atol=10 * 1e-9 * 2.2)
    assert np.abs(q[:, 3:6]).max() < 1e-9


def test_every_joint_type_holds_its_equations_at_every_row():
    """tests/decks/all_joints.xml: every type (and a Constraint_Jprim) on moving bodies; the
    kernel's rows of the equations g (the mu rows of the residual) stay within the tolerance
    at every output row, on both kernels."""
    model = pysolver.load(TEST_DECKS / "all_joints.xml")
    for kind in ("tapes", "generated"):
        res = model.run(kernel=kind)
        assert res.success, res.message
        k = model.compile(kind).kernel
        mu = [m for m in k.layout.mu if m >= 0]
        assert len(mu) == sum(len(pysolver.catalogue.JOINT_EQUATIONS[j.type])
                              for j in model.joints.values())
        worst = max(np.abs(k.residual_array(t, y, yp)[mu]).max()
                    for t, y, yp in zip(res.t, res.y, res.yp))
        assert worst < 1e-7


def test_redundant_equations_are_removed_and_logged():
    """Bricard's mechanism (IFToMM A04) has one redundant equation: it is named in the log,
    and the run keeps the loop closed and the energy."""
    text = _with((JOINTS / "iftomm_a04_bricard.xml").read_text(), end_time=1.0)
    res = pysolver.loads(text).run()
    assert res.success, res.message
    assert any("redundant constraints removed (1)" in line for line in res.log), res.log


BAD = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/><Reference_Marker id="2" body_id="1"/>
  <Reference_Marker id="20" body_id="2"/><Reference_Marker id="21" body_id="2"/>
  <Reference_Marker id="30" body_id="3"/>
  <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
  <Body_Point id="3" cg_id="30" mass="1"/>
  {joint}</Model>
  <Simulate analysis_type="Transient" end_time="0.1" print_interval="0.1"/></MotionSolve>"""


@pytest.mark.parametrize("joint, attribute, words", [
    ('type="REVOLUTE" i_marker_id="20" j_marker_id="21"', "j_marker_id", "different bodies"),
    ('type="REVOLUTE" i_marker_id="1" j_marker_id="2"', "j_marker_id", "both markers are on "
                                                                     "ground"),
    ('type="SPHERICAL" i_marker_id="99" j_marker_id="1"', "i_marker_id", "marker 99 does not"),
    ('type="RACK_PINION" i_marker_id="20" j_marker_id="1"', "pitch_diameter",
     "RACK_PINION joint needs pitch_diameter"),
    ('type="RACK_PINION" i_marker_id="20" j_marker_id="1" pitch_diameter="-1"',
     "pitch_diameter", "a finite length > 0"),
    ('type="SCREW" i_marker_id="20" j_marker_id="1"', "pitch", "SCREW joint needs pitch"),
    ('type="SCREW" i_marker_id="20" j_marker_id="1" pitch="0"', "pitch", "not 0"),
    ('type="REVOLUTE" i_marker_id="20" j_marker_id="1" pitch="0.1"', "pitch",
     "pitch belongs to a SCREW joint, not a REVOLUTE"),
    ('type="REVOLUTE" i_marker_id="30" j_marker_id="1"', "i_marker_id", "point body 3"),
    ('type="HINGE" i_marker_id="20" j_marker_id="1"', "type", "REVOLUTE"),
    ('i_marker_id="20" j_marker_id="1"', "type", "required"),
])
def test_a_bad_joint_is_a_deck_error_naming_it(joint, attribute, words):
    with pytest.raises(DeckError) as err:
        pysolver.loads(BAD.format(joint=f'<Constraint_Joint id="7" {joint}/>'))
    e = err.value
    assert (e.element, e.attribute, e.line) == ("Constraint_Joint", attribute, 7)
    assert words in str(e)


def test_a_joint_that_cannot_be_assembled_fails_the_run_naming_it():
    """Two spherical joints that hold one body's two markers 1 m apart to one ground point."""
    text = BAD.format(joint='<Reference_Marker id="22" body_id="2" pos_x="1"/>'
                            '<Constraint_Joint id="7" type="SPHERICAL" i_marker_id="21" '
                            'j_marker_id="1"/><Constraint_Joint id="8" type="SPHERICAL" '
                            'i_marker_id="22" j_marker_id="1"/>')
    res = pysolver.loads(text).run()
    assert not res.success
    assert "cannot be assembled" in res.message and "Constraint_Joint" in res.message


def test_joint_reactions_on_the_pendulum_are_m_a_minus_m_g():
    """res.joint(1) and JOINT(1, 0, comp, 0) against the reference's joint force on the body
    (m a - m g, benchmarks/data), within 1e-4 N of up to 30 N at integr_tol 1e-9 (measured
    2.5e-5 on the tapes, 5.6e-5 generated: the reaction rests on the accelerations); the
    ground gets the opposite force, and a pin passes no torque about its axis."""
    ref = json.loads((ROOT / "benchmarks" / "data" / "joint_references.json").read_text())
    table = ref["problems"]["pendulum_revolute"]
    text = (JOINTS / "pendulum_revolute.xml").read_text().replace(
        "</Model>", '<Post_Request id="9" expr1="JOINT(1,0,2,0)" expr2="JOINT(1,0,3,0)" '
                    'expr3="JOINT(1,0,8,0)" expr4="JOINT(1,1,3,0)"/></Model>')
    model = pysolver.loads(text)
    for kind in ("tapes", "generated"):
        res = model.run(integr_tol=1e-9, kernel=kind)
        assert res.success, res.message
        rows = np.searchsorted(res.t, table["times"])
        on_i, on_j, req = res.joint(1)[rows], res.joint(1, 1)[rows], res.request(9)[rows]
        assert np.abs(on_i[:, 1] - table["joint_force_on_body_x"]).max() < 1e-4
        assert np.abs(on_i[:, 2] - table["joint_force_on_body_y"]).max() < 1e-4
        np.testing.assert_allclose(req[:, :2], on_i[:, 1:3], rtol=0, atol=1e-12)
        np.testing.assert_allclose(on_j[:, 1:4], -on_i[:, 1:4], rtol=0, atol=1e-12)
        np.testing.assert_allclose(req[:, 3], -req[:, 1], rtol=0, atol=1e-12)
        assert np.abs(on_i[:, 7]).max() < 1e-9 and np.abs(req[:, 2]).max() < 1e-9
        np.testing.assert_allclose(on_i[:, 0], np.linalg.norm(on_i[:, 1:4], axis=1))


RESTING = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1" pos_z="-2"/><Reference_Marker id="2" body_id="1"/>
  <Reference_Marker id="20" body_id="2"/>
  <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="0.1" inertia_yy="0.2" inertia_zz="0.25"/>
  <Reference_Marker id="30" body_id="3" pos_x="1"/><Reference_Marker id="31" body_id="3"/>
  <Body_Rigid id="3" cg_id="30" mass="3" inertia_xx="0.1" inertia_yy="0.2" inertia_zz="0.25"/>
  <Force_Gravity grav_y="-9.81"/>
  <Constraint_Joint id="1" type="TRANSLATIONAL" i_marker_id="20" j_marker_id="1"/>
  <Constraint_Joint id="2" type="FIXED" i_marker_id="31" j_marker_id="2"/>
  <Post_Request id="1" expr1="JOINT(1,1,6,0)" expr2="JOINT(1,1,3,0)" expr3="JOINT(1,0,3,0)"
    expr4="JOINT(1,0,5,0)" expr5="JOINT(1,1,6,1)" expr6="JOINT(2,0,3,0)" expr7="JOINT(2,0,8,0)"
    expr8="JOINT(2,1,8,0)"/>
  <Param_Transient integr_tol="1e-8"/></Model>
  <Simulate analysis_type="Transient" end_time="1" print_interval="0.5"/></MotionSolve>"""


def test_joint_reactions_hold_resting_bodies_as_by_hand():
    """A 2 kg body resting on a horizontal rail (TRANSLATIONAL along z, J 2 m behind I): the
    rail carries m g at I and no torque there; at J, 2 m away, the ground feels the weight
    and its moment about J, (0, 0, 2) x (0, -m g, 0) = (2 m g, 0, 0). A 3 kg cantilever
    (FIXED at its end, centre of mass 1 m out along x): the joint carries m g and the
    torque m g L about z, on I's body and, opposite, on the ground (oI = oJ)."""
    res = pysolver.loads(RESTING).run()
    assert res.success, res.message
    q = res.request(1)
    g = 9.81
    np.testing.assert_allclose(q[:, 0], 2 * 2 * g, rtol=1e-9)       # JOINT(1,1,6,0)
    np.testing.assert_allclose(q[:, 1], -2 * g, rtol=1e-9)          # at J, down
    np.testing.assert_allclose(q[:, 2], 2 * g, rtol=1e-9)           # at I, up
    assert np.abs(q[:, 3]).max() < 1e-9                             # no torque at I
    np.testing.assert_allclose(q[:, 4], 2 * 2 * g, rtol=1e-9)       # in marker 1's axes
    np.testing.assert_allclose(q[:, 5], 3 * g, rtol=1e-9)
    np.testing.assert_allclose(q[:, 6], 3 * g * 1.0, rtol=1e-9)     # m g L on the beam
    np.testing.assert_allclose(q[:, 7], -3 * g * 1.0, rtol=1e-9)    # and on the ground
    np.testing.assert_allclose(res.joint(2)[:, 7], q[:, 6], rtol=1e-12)


def test_joint_function_errors_name_the_joint():
    text = RESTING.replace('expr8="JOINT(2,1,8,0)"', 'expr8="JOINT(7,1,8,0)"')
    with pytest.raises(DeckError, match="joint id 7, which does not exist"):
        pysolver.loads(text)
    with pytest.raises(DeckError, match="jflag is 0 or 1 and comp is 1..8"):
        pysolver.loads(RESTING.replace('expr8="JOINT(2,1,8,0)"', 'expr8="JOINT(2,1,9,0)"'))
    with pytest.raises(KeyError, match="no Constraint_Joint 5"):
        pysolver.loads(RESTING).run().joint(5)


def test_an_assembly_analysis_assembles_and_stops():
    """Simulate analysis_type="Assembly": the pendulum's marker I placed 1 cm off its pivot is
    pulled onto it with the least change (one row, the joint's gap closed); a transient after
    it starts from the assembled state; an Assembly takes no end time."""
    text = (JOINTS / "pendulum_revolute.xml").read_text()
    text = re.sub(r'<Simulate [^>]*/>', '<Simulate analysis_type="Assembly"/>', text)
    text = text.replace('id="20" body_id="2" pos_x="2"', 'id="20" body_id="2" pos_x="2.01"')
    text = text.replace('id="21" body_id="2" pos_x="0"', 'id="21" body_id="2" pos_x="0.01"')
    res = pysolver.loads(text).run()
    assert res.success, res.message
    assert len(res.t) == 1 and res.t[0] == 0.0
    q = res.request(1)
    assert abs(q[0, 0] - 2.0) < 1e-12 and abs(q[0, 6]) < 1e-12          # moved back 1 cm
    both = text.replace('<Simulate analysis_type="Assembly"/>',
                        '<Simulate analysis_type="Assembly"/><Simulate analysis_type="Transient" '
                        'end_time="0.5" print_interval="0.25"/>')
    res = pysolver.loads(both).run()
    assert res.success, res.message
    np.testing.assert_allclose(res.t, [0.0, 0.25, 0.5])          # one row at t = 0
    assert np.abs(res.request(1)[:, 6]).max() < 1e-9
    with pytest.raises(DeckError, match="an Assembly analysis takes no end time"):
        pysolver.loads(text.replace('analysis_type="Assembly"',
                                    'analysis_type="Assembly" end_time="1"'))


def test_a_mass_changed_by_params_runs_as_the_edited_deck():
    """The constraint rows' compliance follows the run's numbers: a pendulum made 1000x
    heavier through params= runs as the deck edited to that mass (it ran 100x less accurately
    when the compliance kept the deck's weight)."""
    deck = (JOINTS / "pendulum_revolute.xml").read_text()
    heavy = pysolver.loads(deck.replace('cg_id="20" mass="1"', 'cg_id="20" mass="1000"'))
    model = pysolver.loads(deck)
    model.run()
    for tol in (1e-6, 1e-8):
        a = model.run(integr_tol=tol, params={"Body_Rigid/2/mass": 1000.0})
        b = heavy.run(integr_tol=tol)
        assert a.success and b.success
        np.testing.assert_allclose(a.request(1)[:, :4], b.request(1)[:, :4], rtol=0, atol=1e-9)


PY_PENDULUM = """from pysolver.msolve import *
import math
PART(1, GROUND=True)
MARKER(2, PART=1)
MARKER(20, PART=2, QP=[2, 0, 0])
MARKER(21, PART=2)
PART(2, MASS=1, CM=20, IP=[1e-3, 1e-3, 1e-3])
ACCGRAV(JGRAV=-9.81)
JOINT(1, TYPE="REVOLUTE", I=21, J=2)
{request}
INTEGRATOR(ERROR=1e-9)
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.1)
"""


def test_a_traced_python_routine_reads_the_joint_reaction():
    """py_sysfnc("JOINT", [id, jflag, comp, rm]) in a Python REQSUB equals JOINT() in an
    expression, channel for channel (the routine is traced into the kernel)."""
    routine = '''
def reqsub(id, time, par, npar, iflag):
    return [py_sysfnc("JOINT", [1, 0, c, 0])[0] for c in (1, 2, 3, 4)] + [
        py_sysfnc("JOINT", [1, 1, c, 20])[0] for c in (2, 3, 6, 8)]
REQUEST(1, FUNCTION="USER()", ROUTINE=reqsub)'''
    exprs = ", ".join([f'F{k + 1}="JOINT(1, 0, {c}, 0)"' for k, c in enumerate((1, 2, 3, 4))]
                      + [f'F{k + 5}="JOINT(1, 1, {c}, 20)"' for k, c in enumerate((2, 3, 6, 8))])
    ref = pysolver.loads(PY_PENDULUM.format(request=f"REQUEST(1, {exprs})"), fmt="py").run()
    res = pysolver.loads(PY_PENDULUM.format(request=routine), fmt="py").run()
    assert ref.success and res.success
    np.testing.assert_allclose(res.request(1), ref.request(1), rtol=0, atol=1e-9)
    # |F| on the bob at most 3 m g (at the bottom, for a point mass), nearly that at t = 0.7
    assert 25.0 < ref.request(1)[:, 0].max() <= 3 * 9.81


def test_loadcontrol_drives_a_body_held_on_a_line():
    """decks/loadcontrol_bed.py with its indenter held on the vertical line through its start
    by an INLINE primitive: LoadControl still drives it (the same 120 updates and the same
    final load as the free indenter, whose contacts are symmetric), and it stays on the
    line while the primitive carries the sideways contact forces."""
    text = (ROOT / "decks" / "loadcontrol_bed.py").read_text()
    at = text.index("LOADCONTROL(")
    held = (text[:at] + 'MARKER(3, PART=1, QP=[W / 2, 0, 0])\n'
            'JPRIM(1, TYPE="INLINE", I=10, J=3)\n'
            'REQUEST(2, F1="DX(10)", F2="DY(10)")\n' + text[at:])
    free = pysolver.loads(text, fmt="py").run()
    res = pysolver.loads(held, fmt="py").run()
    assert free.success and res.success, res.message
    a, b = free.controller(1), res.controller(1)
    assert len(a["time"]) == len(b["time"]) == 120
    assert abs(b["measured"][-1] - a["measured"][-1]) < 1e-3 * abs(a["measured"][-1])
    xy = res.request(2)[:, :2]
    assert np.abs(xy - xy[0]).max() < 1e-9
    assert np.isfinite(res.joint(1)).all()


# a part hinged at the origin that cannot move: its centre of mass 500 mm (0.5 m) off the
# hinge along x, gravity along the hinge axis (z), so the hinge carries a moment m g L
HELD_HINGE = """held hinge
UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH={length}, TIME=SECOND
PART/1, GROUND
MARKER/1, PART=1
PART/2, MASS=2.0, CM=201, IP={ip}, {ip}, {ip3}
MARKER/201, PART=2, QP={L},0,0
MARKER/202, PART=2
JOINT/1, REVOLUTE, I=202, J=1
ACCGRAV/KGRAV=-{g}
REQUEST/1, F1=VX(201)\\F2=VY(201)\\F3=VZ(201)\\F4=WX(201)\\F5=WY(201)\\F6=WZ(201)
END
"""


@pytest.mark.parametrize("tol", [1e-3, 1e-6, 1e-9])
@pytest.mark.parametrize("length, scale", [("METER", 1.0), ("MILLIMETER", 1e3)])
def test_a_hinge_carrying_a_moment_holds_its_part_still_in_any_length_unit(length, scale, tol):
    """The joint's angular rate rows are as compliant as a reaction moment of the bodies'
    effective inertia about the hinge makes them (build/compliance.py): in millimetres the
    total mass alone let the part turn at 5e-4 rad/s at integr_tol 1e-3 (its centre of mass
    at 250 x the tolerance in mm/s), and from 1e-6 IDA failed at t = 0. Now both units give
    the same picture: a reaction of the bodies' weight moves a rate by the tolerance
    (docs/numerics.md, "Constraints"), so the still part's velocity shows the pin's and the
    moment's share, 1.25 integr_tol at its centre of mass (model units per second) and
    0.5 integr_tol / L for its rotation; bound here by twice that."""
    deck = HELD_HINGE.format(length=length, L=0.5 * scale, ip=1e-2 * scale ** 2,
                             ip3=1e-3 * scale ** 2, g=9.80665 * scale)
    res = pysolver.loads(deck, fmt="adm").run(integr_tol=tol)
    assert res.success, res.message
    v = res.request(1)
    assert np.abs(v[:, :3]).max() <= 2 * tol
    assert np.abs(v[:, 3:6]).max() <= 2 * tol / (0.5 * scale)
