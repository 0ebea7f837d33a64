"""Output rows take their accelerations and reactions exact at their positions and velocities
(ps_row_exact, options.reactions = "exact"): IDA's error test leaves the reactions out and
holds the accelerations only to about the tolerance over a step, so a driven rod's torque
carried 2 % of noise at integr_tol 1e-3 and 0.17 % at 1e-6 (trial 43)."""
import numpy as np
import pytest

import pysolver

# a 2 kg rod on a revolute about z at the origin, its centre of mass 0.5 m along x, driven by
# theta = sin(3 t) under gravity -y: the driving torque is (Icm + m a^2) theta'' + m g a cos
ROD = """from pysolver.msolve import *
model = Model()
Accgrav(jgrav=-9.81)
ground = Part(ground=True)
o = Marker(body=ground)
rod = Part(mass=2.0, ip=[0.1, 0.1, 0.1])
rod.cm = Marker(body=rod, qp=[0.5, 0, 0])
pin = Marker(body=rod)
hinge = Joint(type="REVOLUTE", i=pin, j=o)
Motion(joint=hinge, jtype="ROTATION", function="SIN(3*TIME)")
Request(f1=f"WDTZ({rod.cm.id})", f2=f"ACCX({rod.cm.id})", f3=f"ACCY({rod.cm.id})")
model.simulate(type="DYNAMICS", end=2, dtout=0.01)
"""


def _torque(t):
    th = np.sin(3 * t)
    return (0.1 + 2 * 0.25) * (-9 * th) + 2 * 9.81 * 0.5 * np.cos(th)


@pytest.mark.parametrize("tol, bound", [(1e-3, 1e-4), (1e-6, 1e-7), (1e-9, 1e-8)])
def test_a_driven_rod_s_torque_and_accelerations_are_the_closed_form(tol, bound):
    """The motion's torque within `bound` of its largest value at every row (measured 4e-6,
    4e-9 and 2e-10 relative; the reactions' rates at their exact zero: IDA's, out of the
    error test, left 3e-3 at 1e-3 through the rate rows' compliance), and the centre of
    mass's accelerations those of the prescribed rotation, on both kernels alike."""
    model = pysolver.loads(ROD, fmt="py")
    for kernel in ("tapes", "generated"):
        res = model.run(integr_tol=tol, kernel=kernel)
        assert res.success, res.message
        t, T = res.t, _torque(res.t)
        assert np.abs(res.motion(1) - T).max() <= bound * np.abs(T).max()
        th, w, a = np.sin(3 * t), 3 * np.cos(3 * t), -9 * np.sin(3 * t)
        want = np.column_stack([a, -0.5 * (a * np.sin(th) + w ** 2 * np.cos(th)),
                                0.5 * (a * np.cos(th) - w ** 2 * np.sin(th))])
        assert np.abs(res.request(1)[:, :3] - want).max() <= bound * np.abs(want).max()


def test_the_integrator_s_reactions_on_request_keep_the_same_trajectory():
    """reactions="integrator" gives IDA's corrector values (the rows' reactions and
    accelerations differ) on the very same positions and velocities: the option changes what
    the rows report, not the run (but for a LoadControl update on a print time, which
    measures its load on the row's accelerations: docs/numerics.md)."""
    model = pysolver.loads(ROD, fmt="py")
    exact, raw = model.run(), model.run(reactions="integrator")
    assert exact.success and raw.success
    assert exact.stats["steps"] == raw.stats["steps"]
    moving = [i for i, n in enumerate(exact.state_names) if n.startswith("body")]
    np.testing.assert_array_equal(exact.y[:, moving], raw.y[:, moving])
    assert np.abs(exact.motion(1) - raw.motion(1)).max() > 1e-6
    with pytest.raises(ValueError, match="reactions must be 'exact', 'integrator'"):
        model.run(reactions="corrector")


# a pendulum on a revolute driven by 0.5 sin(2 pi t), held still at every instant of a
# quasi-static run: its torque is the weight's moment m g L cos(theta)
QUASI = """<MotionSolve><Model>
<Units mass="KILOGRAM" length="METER" time="SECOND" force="NEWTON"/>
<Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="2" body_id="1"/>
<Reference_Marker id="20" body_id="2" pos_x="2"/><Reference_Marker id="21" body_id="2"/>
<Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1e-3" inertia_yy="1e-3" inertia_zz="1e-3"/>
<Force_Gravity grav_y="-9.81"/>
<Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="2"/>
<Motion_Joint id="1" joint_id="1" motion_type="R" expr="0.5*SIN(2*PI*TIME)"/>
<Post_Request id="1" expr1="AZ(21,2)" expr2="MOTION(1,0,8,0)" expr3="ACCY(20)"/>
<Param_Static method="FIM_S"/></Model>
<Simulate analysis_type="Quasi-Static" end_time="0.5" print_interval="0.125"/></MotionSolve>"""


def test_static_rows_keep_the_equilibrium_s_reactions():
    """A static row is not solved as a dynamic one (its accelerations zero, the torque the
    weight's moment): the exact rows gave -37.4 and -61.8 N m for 18.4 and 17.2 (review 43)."""
    res = pysolver.loads(QUASI).run()
    assert res.success, res.message
    q = res.request(1)
    np.testing.assert_allclose(q[:, 1], 19.62 * np.cos(q[:, 0]), rtol=1e-6)
    assert np.abs(q[:, 2]).max() == 0.0


def test_a_row_by_a_singular_configuration_keeps_the_integrator_s_values():
    """IFToMM A02's four-bar with a row about 3e-8 m from its singular (horizontal) position:
    there the saddle-point system is ill-conditioned (pin forces of 2.7e7 N for 25, the
    crank's acceleration 13.55 for 11.772) and the row keeps IDA's values, which the rate
    rows' compliance holds: the pin force stays of the bodies' weight, and the crank's
    angular acceleration is the closed form on the parallelogram branch, (2 m g L/2 + m g L)
    / (2 (1/12 + 1/4) + 1) = 11.772 rad/s^2."""
    import sys

    from helpers import DECKS
    sys.path.insert(0, str(DECKS / "joints"))
    import make_a02
    T = 0.7084499833806469
    res = pysolver.loads(make_a02.deck(n=1, end=T, dt=T / 4)).run(progress=False)
    assert res.success, res.message
    assert np.abs(res.request(1)[-1, 1]) < 1e-6              # at the crossing
    assert np.abs(np.asarray(res.joint(1))[:, 0]).max() < 100.0
    assert abs(abs(res.yp[-1, res.state_names.index("body2.wz")]) - 11.772) < 1e-3


ROUTINE_PAST_ITS_TABLE = """from pysolver.msolve import *
def torque(id, time, par, npar, dflag, iflag):
    if time > 1.0:                     # a measured table over 0..1 s, nothing past it
        raise ValueError("time %r past the table's end" % time)
    return 0.1 * time
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(20, PART=2, QP=[0.5, 0, 0])
MARKER(21, PART=2)
PART(2, MASS=1, IP=[1e-3, 1e-3, 1e-3], CM=20)
JOINT(1, TYPE='REVOLUTE', I=21, J=1)
MARKER(31, PART=3)
PART(3, MASS=1, IP=[1e-3, 1e-3, 1e-3], CM=31)
JOINT(2, TYPE='TRANSLATIONAL', I=31, J=1)
MOTION(1, JOINT=2, TYPE='TRANSLATION', FUNCTION='0.1*TIME')
SFORCE(1, I=21, J=1, ROTATION=True, FUNCTION="USER()", ROUTINE=torque)
SIMULATE(TYPE='TRANSIENT', END=1.0, DTOUT=0.1)
"""


def test_a_routine_failing_past_the_run_s_end_is_the_row_s_business():
    """The row's solve looks 1e-6 s past it (the motions' time derivative from after the
    row): a routine that raises there, past the run's end, failed the run (-400); the last
    row now keeps IDA's values and the run succeeds, as with reactions="integrator"."""
    model = pysolver.loads(ROUTINE_PAST_ITS_TABLE, fmt="py")
    exact, raw = model.run(progress=False), model.run(progress=False, reactions="integrator")
    assert exact.success and raw.success, exact.message
    assert len(exact.t) == len(raw.t) == 11


# a 1 kg pendulum 2 m from its revolute, released horizontally, with a friction torque that
# reads the hinge's force magnitude (the joint carries nothing at the start)
FRICTION = """<MotionSolve><Model>
<Units mass="KILOGRAM" length="METER" time="SECOND" force="NEWTON"/>
<Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="2" body_id="1"/>
<Reference_Marker id="20" body_id="2" pos_x="2"/><Reference_Marker id="21" body_id="2"/>
<Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1e-3" inertia_yy="1e-3" inertia_zz="1e-3"/>
<Force_Gravity grav_y="-9.81"/>
<Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="2"/>
<Force_Scalar_TwoBody id="5" type="TORQUE" i_marker_id="21" j_marker_id="2"
  expr="-0.05*JOINT(1,0,1,0)*TANH(WZ(21,2)*100)"/>
<Post_Request id="1" expr1="KE(2) + 9.81*DY(20)" expr2="JOINT(1,0,1,0)"/>
<Param_Transient integr_tol="1e-8"/>
</Model><Simulate analysis_type="Transient" end_time="2" print_interval="0.01"/></MotionSolve>"""


def test_a_force_reading_a_joint_force_s_magnitude_runs_from_a_joint_carrying_nothing():
    """|F| of a joint is sqrt(Fx^2 + Fy^2 + Fz^2), whose derivative is infinite where the
    joint carries nothing (its reactions as the consistent start's Newton iteration begins):
    the run started with a NaN (review 43); the magnitude is now 0 with zero derivatives
    there. At the release the pin carries m g Icm / (Icm + m L^2) (the friction is zero at
    rest); the friction only takes energy: the pendulum's energy never rises (to the
    tolerance) and ends below its start."""
    res = pysolver.loads(FRICTION).run()
    assert res.success, res.message
    energy, force = res.request(1)[:, 0], res.request(1)[:, 1]
    assert force[0] == pytest.approx(9.81 * 1e-3 / (1e-3 + 4.0), rel=1e-9)
    assert force.max() > 9.81
    assert np.diff(energy).max() <= 1e-6
    assert energy[-1] < energy[0] - 1e-2
