"""AXU, AYU, AZU (MotionSolve's unwrapped AX, AY, AZ; tracked angles) count every turn: a
torsion spring written as -k AZU past half a turn against SciPy and its energy, spinning
bodies whose angles grow as w t through several turns, the principal value at the start,
statics that follow the angle from the start; AX, AY, AZ keep their value in (-pi, pi]
(docs/deck-language.md, "Angles and requests": tracking them all ran away on tumbling
bodies), and so do the elements that measure their own small angles."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pysolver

# trial 44's deck: a 1 kg m^2 disc on a revolute, an Adams torsion spring -10 AZU, given
# 12 rad/s: theta = 12 / sqrt(10) sin(sqrt(10) t), up to 3.79 rad
TORSION_ADM = """torsion SFORCE with AZ past pi
UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND
PART/1, GROUND
MARKER/1, PART=1
PART/2, MASS=1, CM=20, IP=1,1,1, WZ=12
MARKER/20, PART=2
MARKER/21, PART=2
JOINT/1, REVOLUTE, I=21, J=1
SFORCE/1, I=21, J=1, ROTATION, FUNCTION=-10*AZU(21,1)
REQUEST/1, F1=AZU(21,1)\\F2=AZ(21,1)\\F3=WZ(21,1,1)\\F4=SFORCE(1,0,8,0)\\F5=KE(2)
END
"""

TORSION_XML = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
  <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"
              w_ic_z="12"/>
  <Reference_Marker id="20" body_id="2"/><Reference_Marker id="21" body_id="2"/>
  <Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="1"/>
  <Force_Scalar_TwoBody id="1" type="Torque" i_marker_id="21" j_marker_id="1"
                        expr="-10*AZU(21,1)"/>
  <Post_Request id="1" expr1="AZU(21,1)" expr2="AZ(21,1)" expr3="WZ(21,1,1)"
                expr4="SFORCE(1,0,8,0)" expr5="KE(2)"/>
</Model><Simulate analysis_type="Transient" end_time="2" print_interval="0.005"/>
</MotionSolve>"""


@pytest.mark.parametrize("form", ["adm", "xml"])
def test_a_torsion_spring_on_az_swings_past_half_a_turn_and_back(tmp_path, form):
    """-10 AZU with the disc given 12 rad/s: a harmonic swing to 3.79 rad (past pi) and back,
    against SciPy's DOP853 at rtol 1e-11 within 1e-7 rad and rad/s at integr_tol 1e-10
    (measured 1.9e-8 and 6.0e-8)
    (before: AZ wrapped to -pi, the torque flipped by 2 pi k and the disc spun away with WZ
    +8.87 at 1 s); the torque -10 AZ has no jump; kinetic plus spring energy constant within
    1e-8 of its 72 J (measured 4.5e-9)."""
    if form == "adm":
        path = tmp_path / "torsion.adm"
        path.write_text(TORSION_ADM)
        model = pysolver.load(path, simulate={"analysis_type": "TRANSIENT", "end_time": 2,
                                              "num_step": 400})
        res = model.run(integr_tol=1e-10)
    else:
        res = pysolver.loads(TORSION_XML).run(integr_tol=1e-10)
    assert res.success, res.message
    t, q = res.t, res.request(1)
    ref = solve_ivp(lambda _, y: [y[1], -10 * y[0]], (0, t[-1]), [0, 12], t_eval=t,
                    method="DOP853", rtol=1e-11, atol=1e-12).y
    assert q[:, 0].max() > np.pi + 0.5
    assert np.abs(q[:, 0] - ref[0]).max() < 1e-7
    assert np.abs(q[:, 2] - ref[1]).max() < 1e-7
    np.testing.assert_allclose(q[:, 1], np.angle(np.exp(1j * q[:, 0])), rtol=0, atol=1e-12)
    np.testing.assert_allclose(q[:, 3], -10 * q[:, 0], rtol=0, atol=1e-9)
    assert np.abs(np.diff(q[:, 3])).max() < 1.0               # 62.8 where AZ jumped
    energy = q[:, 4] + 0.5 * 10 * q[:, 0] ** 2
    assert np.abs(energy - 72.0).max() < 1e-8 * 72


SPIN = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
  {bodies}
  <Post_Request id="1" expr1="AXU(30)" expr2="AYU(31,1)" expr3="AZU(32)" expr4="AZU(33)"
                expr5="AZU(34)" expr6="AZU(35)"/>
</Model><Simulate analysis_type="Transient" end_time="3" print_interval="0.01"/>
</MotionSolve>"""


def _spinner(k, axis, w, psi=0.0):
    return (f'<Reference_Marker id="{30 + k}" body_id="{3 + k}" pos_x="{k}" psi="{psi}"/>'
            f'<Body_Rigid id="{3 + k}" cg_id="{30 + k}" mass="1" inertia_xx="0.3" '
            f'inertia_yy="0.3" inertia_zz="0.3" w_ic_{axis}="{w}"/>')


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_spinning_bodies_read_w_t_through_several_turns(kernel):
    """Bodies spun at 7 rad/s about x, y and z (3.3 turns in 3 s) read AXU, AYU, AZU = 7 t;
    bodies that start turned read the principal value there and go on from it without a
    jump: psi 3.0 spun at -2 rad/s reads 3 - 2 t down to -3; psi 200 degrees reads
    200 - 360 = -160 degrees at the start (the value in (-pi, pi], as Adams starts) and then
    -160 degrees + 2 t; psi 3.1 spun at +2 reads 3.1 + 2 t past pi (to 9.1). All within
    1e-8 at integr_tol 1e-11 (measured 1.4e-9)."""
    bodies = "".join(_spinner(k, axis, 7.0) for k, axis in enumerate("xyz"))
    bodies += _spinner(3, "z", -2.0, psi=3.0) + _spinner(4, "z", 2.0, psi=np.radians(200))
    bodies += _spinner(5, "z", 2.0, psi=3.1)
    res = pysolver.loads(SPIN.format(bodies=bodies)).run(kernel=kernel, integr_tol=1e-11)
    assert res.success, res.message
    t, q = res.t, res.request(1)[:, :6]
    expected = np.column_stack([7 * t, 7 * t, 7 * t, 3.0 - 2 * t,
                                np.radians(200) - 2 * np.pi + 2 * t, 3.1 + 2 * t])
    assert expected[:, 2].max() > 6 * np.pi
    np.testing.assert_allclose(q, expected, rtol=0, atol=1e-8)


STATIC = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
  <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
  <Reference_Marker id="20" body_id="2"/>
  <Constraint_Joint id="1" type="REVOLUTE" i_marker_id="20" j_marker_id="1"/>
  <Force_Scalar_TwoBody id="1" type="Torque" i_marker_id="20" j_marker_id="1"
                        expr="-10*(AZU(20,1) - 5)"/>
  <Post_Request id="1" expr1="AZU(20,1)" expr2="SFORCE(1,0,8,0)"/>
  <Param_Static method="{method}" max_imbalance="1e-10" max_error="1e-10"/>
</Model><Simulate analysis_type="Static" end_time="0"/></MotionSolve>"""


@pytest.mark.parametrize("method", ["FIM_S", "MKEAM"])
def test_statics_follow_the_angle_from_the_start(method):
    """Statics: a torsion spring -10 (AZU - 5) pulls the disc from 0 to AZ = 5 rad, past pi,
    through the turn (FIM_S's increments stay under half a turn, MKEAM swings there), and
    rests with no torque: the angle is tracked from its value at the start, 0, so the
    equilibrium is 5, not 5 - 2 pi (where the torque would be 62.8 N m)."""
    res = pysolver.loads(STATIC.format(method=method)).run(integr_tol=1e-9)
    assert res.success, res.message
    az, torque = res.request(1)[-1, :2]
    assert az == pytest.approx(5.0, abs=1e-7)
    assert torque == pytest.approx(0.0, abs=1e-6)


BUSHED = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
  <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"
              w_ic_z="12"/>
  <Reference_Marker id="20" body_id="2"/>
  <Constraint_Joint id="1" type="REVOLUTE" i_marker_id="20" j_marker_id="1"/>
  <Force_Bushing id="1" i_marker_id="20" j_marker_id="1" ktz="10"/>
  <Post_Request id="1" expr1="AZU(20,1)" expr2="BUSH(1,0,8,0)"/>
</Model><Simulate analysis_type="Transient" end_time="1" print_interval="0.01"/>
</MotionSolve>"""


def test_a_bushing_keeps_its_small_angles_in_the_half_turn():
    """A bushing's angles are Adams' "projected, small-angle rotational displacements": its
    torque -ktz AZ reads the value in (-pi, pi] (a decision: no turns tracked), so the disc
    given 12 rad/s on a bushing of 10 N m/rad passes pi and its torque changes sign there,
    while the request's AZU counts on; one tracked state, the request's."""
    res = pysolver.loads(BUSHED).run(integr_tol=1e-9)
    assert res.success, res.message
    q = res.request(1)
    wrapped = np.angle(np.exp(1j * q[:, 0]))
    assert q[:, 0].max() > np.pi
    np.testing.assert_allclose(q[:, 1], -10 * wrapped, rtol=0, atol=1e-7)
    assert [n for n in res.state_names if n.endswith(".angle")] == ["AZ_20_1.angle"]


SFOSUB_PY = """
def SFOSUB(id, time, par, npar, dflag, iflag):
    return -par[0] * py_sysfnc("AZ", [21, 1])[0]
"""
SFOSUB_C = r"""
#include "pysolver_usersub.h"
void SFOSUB(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int ids[2] = {21, 1}, err;
  double az;
  c_sysfnc("AZ", ids, 2, &az, &err);
  *value = -par[0] * az;
}
"""


@pytest.mark.parametrize("language", ["python", "c"])
def test_a_routine_reads_az_as_the_expression_does(tmp_path, language):
    """The torsion spring as an SFOSUB (a traced Python routine, a C library) reading
    py_sysfnc / c_sysfnc("AZ", [21, 1]): the value it gets is AZ's, in (-pi, pi], so the disc
    given 2 rad/s (a swing of 0.63 rad) moves as with the expression -10*AZ (within 1e-6 rad
    of it); a routine has no unwrapped angle to read."""
    if language == "python":
        (tmp_path / "sub.py").write_text(SFOSUB_PY)
        routine = f'script_name="{tmp_path / "sub.py"}"'
    else:
        import shutil
        import subprocess
        cc = shutil.which("cc") or shutil.which("gcc")
        if cc is None:
            pytest.skip("no C compiler on this machine to build the test's routine")
        (tmp_path / "sub.c").write_text(SFOSUB_C)
        subprocess.run([cc, "-shared", "-fPIC", f"-I{pysolver.get_include()}",
                        str(tmp_path / "sub.c"), "-o", str(tmp_path / "sub.so")], check=True)
        routine = f'usrsub_dll_name="{tmp_path / "sub.so"}"'
    deck = TORSION_XML.replace('w_ic_z="12"', 'w_ic_z="2"').replace("-10*AZU", "-10*AZ")
    text = deck.replace('expr="-10*AZ(21,1)"', f'{routine} usrsub_param_string="USER(10)"')
    ref = pysolver.loads(deck).run(integr_tol=1e-10)
    res = pysolver.loads(text).run(integr_tol=1e-10)
    assert res.success, res.message
    assert 0.6 < res.request(1)[:, 1].max() < 0.7
    np.testing.assert_allclose(res.request(1)[:, 1], ref.request(1)[:, 1], rtol=0, atol=1e-6)
