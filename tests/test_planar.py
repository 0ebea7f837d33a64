"""Planar scenes (pysolver/build/planar.py): rigid bodies held in the x-y plane by revolutes
about z, loaded by gravity and scalar forces in the plane, run in (x, y, rz) with the
out-of-plane equations left out, give the 3-D model's motion and reactions, conserve energy,
and anything that could leave the plane keeps a scene in 3-D. The planar kinematics' Jacobian and generated C are checked with every test deck
(tests/decks/planar_fourbar.xml in test_jacobian.py and test_codegen.py)."""
import re

import numpy as np
import pytest

import pysolver
from pysolver.build.planar import looks_planar, planar_bodies, why_not
from pysolver.deck.dimensions import state_unit
from pysolver.viewer.poses import Poses

from helpers import DECKS, TEST_DECKS

FOURBAR = (TEST_DECKS / "planar_fourbar.xml").read_text()
MASSES = {20: 1.0, 30: 2.0, 40: 1.5}       # cg marker -> mass


def _run(monkeypatch, planar, text=FOURBAR, **options):
    monkeypatch.setenv("PYSOLVER_PLANAR", planar)
    model = pysolver.loads(text)
    return model, model.run(**options)


def _energy(model, res):
    """Kinetic energy (request 1, channel 8: KE(0)) plus the bodies' potential energy m g y
    of their centres of mass (their cg markers' heights) and the two springs' (request 3:
    the spring's length, the torsion spring's angle)."""
    poses = Poses(model, res.t, res.y, res.state_names)
    springs = res.request(3)
    return (res.request(1)[:, 7] + sum(m * 9.81 * poses.marker_position(mk)[:, 1]
                                       for mk, m in MASSES.items())
            + 0.5 * 20.0 * (springs[:, 0] - 1.5) ** 2 + 0.5 * 3.0 * springs[:, 1] ** 2)


def test_the_four_bar_runs_planar_with_the_3d_models_motion_and_reactions(monkeypatch):
    """Against the 3-D model at 1e-12 (73 unknowns, joint 4's out-of-plane equations found
    redundant): the planar run (34 unknowns) at 1e-11 gives the requests' positions, angles
    and rates within 1e-7, the joints' reactions within 1e-6 relative (measured 2.4e-10 and
    1.3e-8; the 3-D model at 1e-11: 1.5e-9 and 2.2e-8), and exactly nothing out of the
    plane. The scalar forces (a spring and a torsion spring) load the planar bodies as
    (Fx, Fy, Mz). (At 1e-10, with the crank started at its given 2 rad/s since stop 42, the
    reactions' error is 1.1e-6 planar and 2.0e-7 in 3-D: algebraic states, outside IDA's
    error test; at stop 41 the start had the crank at 0.68 rad/s.)"""
    _, ref = _run(monkeypatch, "off", integr_tol=1e-12)
    model, res = _run(monkeypatch, "auto", integr_tol=1e-11)
    assert res.success and ref.success
    assert model.compile().kernel.ny == 34
    assert res.state_names[:6] == ["body2.x", "body2.y", "body2.rz", "body2.vx", "body2.vy",
                                   "body2.wz"]
    assert any("planar scene: 3 bodies" in line for line in res.log)
    assert [state_unit(model, n) for n in res.state_names[:6]] == ["m", "m", "rad", "m/s",
                                                                  "m/s", "rad/s"]
    np.testing.assert_array_equal(res.t, ref.t)
    a, b = res.request(1), ref.request(1)
    assert np.abs(a[:, :6] - b[:, :6]).max() < 1e-7
    assert np.all(a[:, 2] == 0.2)                    # DZ(32): the plane's height
    for jid in (1, 2, 3, 4):
        ja, jb = res.joint(jid), ref.joint(jid)
        assert np.abs(ja - jb).max() <= 1e-6 * np.abs(jb).max()
        # no force along z, no torque about x or y (global components)
        assert np.all(ja[:, 3] == 0.0) and np.all(ja[:, 5:7] == 0.0)


def test_the_planar_four_bar_conserves_energy(monkeypatch):
    """No damping, no work by the joints: kinetic plus potential energy (gravity's and the
    two springs') constant within 1e-8 relative at 1e-10 through 1 s (measured 2.9e-10;
    9.2e-9 at 1e-9, 7.8e-8 at 1e-8)."""
    model, res = _run(monkeypatch, "auto", integr_tol=1e-10)
    e = _energy(model, res)
    assert np.abs(e - e[0]).max() <= 1e-8 * np.abs(e).max()


def test_the_pendulum_and_a02_run_planar(monkeypatch):
    """The revolute pendulum (10 unknowns instead of 23) and IFToMM A02 (970 instead of
    2,023) are planar scenes; PYSOLVER_PLANAR=off keeps them in 3-D."""
    for deck, planar, three_d in (("pendulum_revolute.xml", 10, 23),
                                  ("iftomm_a02_fourbar.xml", 970, 2023)):
        for mode, ny in (("auto", planar), ("off", three_d)):
            monkeypatch.setenv("PYSOLVER_PLANAR", mode)
            assert pysolver.load(DECKS / "joints" / deck).compile().kernel.ny == ny


@pytest.mark.parametrize("change,reason", [
    (('grav_z="0"', 'grav_z="-0.1"'), "gravity has a z component"),
    (('w_ic_z="2"', 'w_ic_z="2" w_ic_x="0.1"'),
     "body 2's initial angular velocity is not about global z"),
    (('w_ic_z="2"', 'w_ic_z="2" v_ic_z="0.1"'), "body 2's initial velocity has a z component"),
    (('inertia_xy="0.01"', 'inertia_xy="0.01" inertia_xz="0.001"'),
     "body 2's inertia has global xz or yz products"),
    (('<Reference_Marker id="4" body_id="1" pos_x="3" pos_z="0.2"/>',       # a tilted axis
      '<Reference_Marker id="4" body_id="1" pos_x="3" pos_z="0.2" theta="0.001"/>'),
     "Constraint_Joint 4's z axes are not along global z"),
    (('<Reference_Marker id="4" body_id="1" pos_x="3" pos_z="0.2"/>',       # off the plane
      '<Reference_Marker id="4" body_id="1" pos_x="3" pos_z="0.2001"/>'),
     "Constraint_Joint 4's markers are not at the height"),
    (('type="REVOLUTE" i_marker_id="41"', 'type="SPHERICAL" i_marker_id="41"'),
     "Constraint_Joint 3 is not a REVOLUTE"),
    (('<Reference_Marker id="20" body_id="2" pos_y="0.5" pos_z="0.2"',      # a joint off a
      '<Reference_Marker id="20" body_id="2" pos_y="0.5" pos_z="0.3"'),     # body's cm height
     "Constraint_Joint 1's markers are not at the height"),
    (('type="Force" i_marker_id="33"', 'type="Force" is_action_only="TRUE" i_marker_id="33"'),
     "Force_Scalar_TwoBody 1 acts out of the plane"),
    (('<Reference_Marker id="5" body_id="1" pos_x="1.5" pos_y="3" pos_z="0.2"/>',  # a slant
      '<Reference_Marker id="5" body_id="1" pos_x="1.5" pos_y="3" pos_z="0.5"/>'),
     "Force_Scalar_TwoBody 1 acts out of the plane"),
    (('<Reference_Marker id="5" body_id="1" pos_x="1.5" pos_y="3" pos_z="0.2"/>',  # off axis
      '<Reference_Marker id="5" body_id="1" pos_x="1.5" pos_y="3" pos_z="0.2"/>'
      '<Reference_Marker id="6" body_id="1" pos_z="0.2" theta="0.3"/>'
      '<Force_Scalar_TwoBody id="3" type="Torque" i_marker_id="43" j_marker_id="6" '
      'expr="1"/>'), "Force_Scalar_TwoBody 3 acts out of the plane"),
    (('<Force_Gravity', '<Force_Vector_OneBody id="1" type="ForceOnly" marker_id="22" '
                        'ref_marker_id="1" fx_expression="1"/><Force_Gravity'),
     "it has vforces (not taken in a planar scene)"),
    (('</Model>', '<Motion_Marker id="1" i_marker_id="22" j_marker_id="1" direction="X" '
                  'val_type="D" expr="0"/></Model>'), "motion 1 is not a rotation about global z"),
    (('</Model>', '<Reference_Marker id="7" body_id="1" pos_z="0.2" theta="0.3"/>'
                  '<Motion_Marker id="1" i_marker_id="21" j_marker_id="7" direction="B3" '
                  'val_type="V" expr="2"/></Model>'), "motion 1 is not a rotation about global z"),
    (('</Model>', '<Reference_Marker id="7" body_id="2" pos_z="0.2" theta="0.3"/>'
                  '<Motion_Marker id="1" i_marker_id="7" j_marker_id="1" direction="B3" '
                  'val_type="V" expr="2"/></Model>'), "motion 1 is not a rotation about global z"),
    (('</MotionSolve>', '<Simulate analysis_type="Static"/></MotionSolve>'),
     "it has a Simulate command that is not Transient"),
])
def test_anything_that_could_leave_the_plane_keeps_the_scene_3d(change, reason):
    """Each change gives the scene something out of the plane, or an element pysolver does
    not reason about: the scene runs in 3-D (no planar body), and why_not says why; a run's
    log says so when all its joints are revolutes about z (a scene that looks planar)."""
    old, new = change
    assert old in FOURBAR
    assert planar_bodies(pysolver.loads(FOURBAR)) == {2, 3, 4}
    model = pysolver.loads(FOURBAR.replace(old, new, 1))
    assert planar_bodies(model) == frozenset()
    assert reason in why_not(model)
    if looks_planar(model):
        assert f"not a planar scene, integrated in 3-D: {why_not(model)}" in \
            model.compile("tapes").notes


def test_planar_off_is_said_in_the_log(monkeypatch):
    monkeypatch.setenv("PYSOLVER_PLANAR", "off")
    res = pysolver.loads(FOURBAR).run(integr_tol=1e-6)
    assert "integrated in 3-D: PYSOLVER_PLANAR=off" in res.log


def test_a_point_body_keeps_the_scene_3d():
    text = (DECKS / "particle_between_lines.xml").read_text()
    assert planar_bodies(pysolver.loads(text)) == frozenset()


def test_sweep_cases_of_a_planar_scene(monkeypatch):
    """A case changing a mass, an inertia or the plane's gravity runs planar and gives the
    3-D model's answer with the same numbers (within 1e-7); a case that leaves the plane is
    a DeckError naming it, and the deck's values are back for the next run."""
    case = {"Body_Rigid/3/mass": 3.0, "Body_Rigid/2/inertia_zz": 0.1,
            "Force_Gravity/grav_x": 1.0}
    monkeypatch.setenv("PYSOLVER_PLANAR", "off")
    ref = pysolver.loads(FOURBAR).run(params=case, integr_tol=1e-11)
    monkeypatch.setenv("PYSOLVER_PLANAR", "auto")
    model = pysolver.loads(FOURBAR)
    plain = model.run(integr_tol=1e-10)
    res = model.run(params=case, integr_tol=1e-10)
    assert res.success and np.abs(res.request(1)[:, :6] - ref.request(1)[:, :6]).max() < 1e-7
    assert np.abs(res.request(1)[:, :2] - plain.request(1)[:, :2]).max() > 1e-3
    with pytest.raises(pysolver.DeckError, match=re.escape(
            "parameters {Force_Gravity/grav_z=-1, Body_Rigid/3/mass=3}: the model was compiled "
            "as a planar scene (docs/numerics.md, \"Planar scenes\") and with these numbers "
            "gravity has a z component; to run them, set PYSOLVER_PLANAR=off and load the "
            "model again (it then runs in 3-D)")):
        model.run(params={"Force_Gravity/grav_z": -1.0, "Body_Rigid/3/mass": 3.0})
    again = model.run(integr_tol=1e-10)
    np.testing.assert_array_equal(again.request(1), plain.request(1))


def test_the_animation_draws_planar_bodies_where_the_3d_run_has_them(monkeypatch):
    """Marker positions and axes from a planar run's states (x, y, rz and the body's axes at
    the start) agree with the 3-D run's within 1e-7 at 1e-11."""
    poses = {}
    for mode in ("off", "auto"):
        model, res = _run(monkeypatch, mode, integr_tol=1e-11)
        poses[mode] = Poses(model, res.t, res.y, res.state_names)
    a, b = poses["auto"], poses["off"]
    for mk in (20, 22, 30, 32, 41, 42):
        assert np.abs(a.marker_position(mk) - b.marker_position(mk)).max() < 1e-7
        assert np.abs(a.marker_axes(mk) - b.marker_axes(mk)).max() < 1e-7


def test_a_runs_start_is_remembered_only_for_the_same_numbers(monkeypatch):
    """The consistent start (assembly, velocities, accelerations and reactions) is computed
    once for equal numbers and again whenever one changes (a case's mass, gravity, the
    tolerance's compliance, another initial velocity): each run's answers and statistics are
    a fresh kernel's, bit for bit."""
    from pysolver.build import consistent
    calls = []
    real = consistent._consistent
    monkeypatch.setattr(consistent, "_consistent", lambda *a: calls.append(1) or real(*a))
    model = pysolver.loads(FOURBAR)
    runs = [({}, 1e-9), ({}, 1e-9), ({"Body_Rigid/3/mass": 3.0}, 1e-9),
            ({"Force_Gravity/grav_x": 1.0}, 1e-9), ({}, 1e-8),
            ({"Body_Rigid/2/w_ic_z": 1.0}, 1e-8), ({"Body_Rigid/2/w_ic_z": 1.0}, 1e-8)]
    for params, tol in runs:
        res = model.run(params=params, integr_tol=tol)
        fresh = pysolver.loads(FOURBAR).run(params=params, integr_tol=tol)
        np.testing.assert_array_equal(res.y, fresh.y)
        np.testing.assert_array_equal(res.yp, fresh.yp)
        assert res.stats == fresh.stats            # a reused start counts its evaluations
    # computed by every run but the two that repeat the one before, and by the fresh models
    assert len(calls) == 2 * len(runs) - 2


def test_a_pivot_above_the_centre_of_mass_keeps_the_pendulum_3d(monkeypatch):
    """The revolute pendulum with its pivot 0.5 m above the centre of mass's plane moves in
    its plane, but its joint carries an out-of-plane torque (the in-plane joint force's
    moment about the centre of mass, 11.3 N m about x at 1 s): the scene runs in 3-D, so its
    reactions are the 3-D model's (a planar run reported zero)."""
    text = (DECKS / "joints" / "pendulum_revolute.xml").read_text()
    for mk in ('id="2" body_id="1"', 'id="21" body_id="2"'):
        old = f'<Reference_Marker {mk} pos_x="0" pos_y="0" pos_z="0"'
        assert old in text
        text = text.replace(old, old[:-2] + '0.5"')
    text = text.replace('end_time="5"', 'end_time="1"')
    assert planar_bodies(pysolver.loads(text)) == frozenset()
    _, ref = _run(monkeypatch, "off", text)
    _, res = _run(monkeypatch, "auto", text)
    assert res.success and ref.success
    np.testing.assert_array_equal(res.joint(1), ref.joint(1))
    assert abs(ref.joint(1)[-1, 5]) > 10.0


def test_a_driven_crank_runs_planar_with_the_3d_models_motion_and_drive(monkeypatch):
    """A Motion_Joint on the crank's revolute (a rotation about z) keeps the scene planar:
    against the 3-D model at 1e-12, positions within 1e-7 and the drive's torque
    (res.motion) and the joints' reactions within 1e-6 relative at 1e-10 (measured
    2.2e-10, and 5.4e-8 and 7.2e-8)."""
    text = FOURBAR.replace("</Model>", '<Motion_Joint id="1" joint_id="1" val_type="D" '
                                        'expr="2*TIME + 0.3*SIN(5*TIME)"/></Model>')
    _, ref = _run(monkeypatch, "off", text, integr_tol=1e-12)
    model, res = _run(monkeypatch, "auto", text, integr_tol=1e-10)
    assert res.success and ref.success
    assert planar_bodies(model) == {2, 3, 4} and model.compile().kernel.ny == 36
    assert np.abs(res.request(1)[:, :6] - ref.request(1)[:, :6]).max() < 1e-7
    drive, drive_ref = res.motion(1), ref.motion(1)
    assert np.abs(drive - drive_ref).max() <= 1e-6 * np.abs(drive_ref).max()
    for jid in (1, 2, 3, 4):
        ja, jb = res.joint(jid), ref.joint(jid)
        assert np.abs(ja - jb).max() <= 1e-6 * np.abs(jb).max()


def test_check_says_how_many_states_run(monkeypatch, tmp_path):
    """`pysolver check` (Model.summary after compiling) gives the count a run integrates,
    and the 3-D model's; res.animate takes the model, and a path is a clear TypeError."""
    monkeypatch.setenv("PYSOLVER_PLANAR", "auto")
    model = pysolver.loads(FOURBAR)
    assert model.summary().splitlines()[-1] == "states: 79"
    model.check()
    assert model.summary().splitlines()[-1] == "states: 34 integrated (79 in 3-D; a planar scene)"
    res = model.run(integr_tol=1e-6)
    with pytest.raises(TypeError, match=re.escape("animate() takes the Model that made the "
                                                  "run, not 'out.html': write the page with "
                                                  "res.animate().save(path)")):
        res.animate("out.html")
