"""Initial velocities made consistent with the joints: the ones a deck gives are kept, the
others take what the constraints need, the least change in kinetic energy, whatever the
units (docs/deck-language.md, "Initial velocities")."""
import math

import numpy as np
import pytest

import pysolver

#: A 1 kg pendulum on a revolute at the origin, its centre of mass 1 m below, inertia 0.1
#: about it, given only its spin w0; in metres (s = 1) or millimetres (s = 1000).
PENDULUM = """<MotionSolve><Model>
<Units mass="KILOGRAM" length="{unit}" time="SECOND" force="NEWTON"/>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="2" body_id="1"/>
<Reference_Marker id="20" body_id="2" pos_y="{r}"/>
<Reference_Marker id="21" body_id="2"/>
<Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="{i}" inertia_yy="{i}" inertia_zz="{i}"
            w_ic_z="0.01" {extra}/>
<Force_Gravity grav_y="{g}"/>
<Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="2"/>
<Post_Request id="1" expr1="WZ(20)" expr2="VX(20)" expr3="AZ(20)"/>
<Param_Transient integr_tol="1e-10"/>
</Model><Simulate analysis_type="Transient" end_time="{T!r}" print_interval="{dt!r}"/>
</MotionSolve>"""
W0, R, INERTIA, G = 0.01, 1.0, 0.1, 9.81
OMEGA = math.sqrt(G * R / (INERTIA + R * R))       # small swings about the bottom


def pendulum(unit="METER", s=1.0, extra=""):
    return pysolver.loads(PENDULUM.format(unit=unit, r=-R * s, i=INERTIA * s * s, g=-G * s,
                                          extra=extra, T=math.pi / OMEGA,
                                          dt=math.pi / OMEGA / 40))


@pytest.mark.parametrize("unit, s", [("METER", 1.0), ("MILLIMETER", 1000.0)])
def test_a_pendulum_given_only_its_spin_keeps_it_in_any_units(unit, s):
    """It kept half its spin in metres and 2e-6 of it in millimetres (all velocities changed
    alike, in the deck's units). Now: the spin as given, its centre of mass at w0 r, and the
    swing of a pendulum started at the bottom with w0, within 1e-5 of its amplitude w0 / omega
    over half a period (a 3.3e-3 rad swing: the small-angle solution's phase is off by about
    theta^2 / 16 = 7e-7 of it; half the spin would be off by 0.5)."""
    model = pendulum(unit, s)
    res = model.run()
    assert res.success, res.message
    assert not any("initial conditions" in line for line in res.log + model.run().log)
    q = res.request(1)
    assert q[0, 0] == pytest.approx(W0, rel=1e-12)
    assert q[0, 1] == pytest.approx(W0 * R * s, rel=1e-12)
    np.testing.assert_allclose(q[:, 2], W0 / OMEGA * np.sin(OMEGA * res.t), rtol=0,
                               atol=1e-5 * W0 / OMEGA)
    np.testing.assert_allclose(q[:, 0], W0 * np.cos(OMEGA * res.t), rtol=0, atol=1e-5 * W0)


def test_given_velocities_that_agree_are_kept_exactly():
    res = pendulum(extra='v_ic_x="0.01"').run()
    assert res.success, res.message
    assert res.request(1)[0, :2] == pytest.approx([W0, W0], rel=1e-14)


def test_the_same_pendulum_as_an_adams_dataset(tmp_path):
    """PART/2 ... WZ=0.01: the Adams form swung at half the analytic amplitude."""
    (tmp_path / "pend.acf").write_text(f"pend\npend\nSIMULATE/DYNAMICS, END={math.pi / OMEGA!r}, "
                                       "STEPS=40\nSTOP\n")
    (tmp_path / "pend.adm").write_text("""pendulum given WZ
UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND
PART/1, GROUND
MARKER/1, PART=1
PART/2, MASS=1, CM=20, IP=0.1,0.1,0.1, WZ=0.01
MARKER/20, PART=2, QP=0,-1,0
MARKER/21, PART=2
JOINT/1, REVOLUTE, I=21, J=1
ACCGRAV/JGRAV=-9.81
REQUEST/1, F1=WZ(20)\\, F2=VX(20)\\, F3=AZ(20)
INTEGRATOR/ERROR=1e-10
END
""")
    res = pysolver.load(tmp_path / "pend.acf").run()
    assert res.success, res.message
    q = res.request(1)
    assert q[0, :2] == pytest.approx([W0, W0], rel=1e-12)
    assert np.abs(q[:, 2]).max() == pytest.approx(W0 / OMEGA, rel=1e-5)


SLEIGH = """<MotionSolve><Model>
<Units mass="KILOGRAM" length="{unit}" time="SECOND" force="NEWTON"/>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="20" body_id="2"/>
<Reference_Marker id="21" body_id="2" pos_x="{a}"/>
<Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="{i}" inertia_yy="{i}" inertia_zz="{iz}"
            v_ic_x="{u}" w_ic_z="0.8" v_ic_y="{v}"/>
<Constraint_Joint id="1" type="PLANAR" i_marker_id="20" j_marker_id="1"/>
<Constraint_General id="5" expr="VY(21, 0, 21)"/>
<Post_Request id="1" expr1="VX(20)" expr2="VY(20)" expr3="WZ(20)"/>
</Model><Simulate analysis_type="Transient" end_time="0.1" print_interval="0.1"/>
</MotionSolve>"""


@pytest.mark.parametrize("unit, s", [("METER", 1.0), ("MILLIMETER", 1000.0)])
def test_given_velocities_that_conflict_change_the_least_in_kinetic_energy(unit, s):
    """A sleigh (m = 2, Iz = 0.2, knife a = 0.3 ahead) given the sideways speed +0.24 that
    its knife forbids (it allows -a w = -0.24): the change (dv, dw) with dv + a dw = -0.48
    that is the least in m dv^2 + Iz dw^2, in metres and millimetres alike."""
    m, iz, a = 2.0, 0.2, 0.3
    text = SLEIGH.format(unit=unit, a=a * s, i=0.1 * s * s, iz=iz * s * s, u=1.0 * s,
                         v=0.24 * s)
    model = pysolver.loads(text)
    res = model.run()
    assert res.success, res.message
    q = res.request(1)[0]
    gap = -0.48
    dv = gap * (1 / m) / (1 / m + a * a / iz)
    dw = gap * (a / iz) / (1 / m + a * a / iz)
    assert q[:3] == pytest.approx([1.0 * s, (0.24 + dv) * s, 0.8 + dw], rel=1e-10)
    assert res.log[-1] == (
        "initial conditions: velocities the deck gives conflict with its constraints and were "
        f"changed, the least in kinetic energy: body2.vy {0.24 * s:.6g} -> {(0.24 + dv) * s:.6g}"
        f", body2.wz 0.8 -> {0.8 + dw:.6g} (docs/deck-language.md, \"Initial velocities\")")
    again = model.run()                        # the start remembered, and its note with it
    assert again.log == res.log and pysolver.loads(text.replace(
        f'v_ic_y="{0.24 * s}"', f'v_ic_y="{-0.24 * s}"')).run().log == []


def test_motionview_ic_flags_say_which_components_are_used():
    """v_ic_*_flag / w_ic_*_flag (MotionView's *SetBodyICFlag: FALSE, do not use that
    component) were unknown attributes. FALSE leaves the component out: the pendulum given
    w_ic_z = 0.01 with its flag FALSE starts at rest; a v_ic_x = 0.05 flagged FALSE beside a
    used spin leaves the centre of mass the velocity the spin needs (w0 r)."""
    flagged = pendulum(extra='w_ic_z_flag="FALSE"').run()
    assert flagged.success and np.abs(flagged.request(1)[0, :2]).max() == 0.0
    both = pendulum(extra='v_ic_x="0.05" v_ic_x_flag="FALSE" w_ic_z_flag="TRUE"').run()
    assert both.request(1)[0, :2] == pytest.approx([W0, W0 * R], rel=1e-12)
    with pytest.raises(pysolver.DeckError, match="expected TRUE or FALSE") as info:
        pendulum(extra='w_ic_z_flag="maybe"')
    assert info.value.attribute == "w_ic_z_flag"
    point = ('<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>'
             '<Reference_Marker id="10" body_id="2"/>'
             '<Body_Point id="2" cg_id="10" mass="1" v_ic_x="1" {flag}/></Model>'
             '<Simulate analysis_type="Transient" end_time="1" print_interval="0.5"/>'
             '</MotionSolve>')
    assert pysolver.loads(point.format(flag='v_ic_x_flag="FALSE"')).bodies[2].vel[0] == 0.0
    with pytest.raises(pysolver.DeckError, match="unknown attribute") as info:
        pysolver.loads(point.format(flag='w_ic_x_flag="TRUE"'))   # a point body has no spin
    assert info.value.attribute == "w_ic_x_flag"
