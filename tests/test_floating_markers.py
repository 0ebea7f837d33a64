"""Floating markers (Adams MARKER ... FLOATING, XML floating="TRUE"): a vector force keeps its
JFLOAT on its I marker (Adams' VFORCE and GFORCE pages: "moves the JFLOAT marker to keep it
superimposed on the I marker"), so measures at it read I's place, axes and motion, and the
reaction there is -F and -T; a fixed J marker keeps its place; a floating marker anywhere but
a vector force's JFLOAT, or floating with two I markers and read, is a DeckError; the flag
survives conversion."""
import numpy as np
import pytest

import pysolver
from pysolver import DeckError
from pysolver.convert import convert

# a 2 kg body given vx 0.3 and wz 3, pushed by FY = 1 (global) and turned by TZ = 0.5 at its
# cg: x = 0.3 t, y = t^2 / 4, its angle 3 t + t^2 / 4 (Izz 1)
PUSHED_ADM = """vector forces on a floating marker
UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND
PART/1, GROUND
MARKER/1, PART=1
MARKER/9, PART=1, FLOATING
PART/2, MASS=2, CM=20, IP=1,1,1, VX=0.3, WZ=3
MARKER/20, PART=2
VFORCE/1, I=20, JFLOAT=9, RM=1, FX=0\\FY=1\\FZ=0
VTORQUE/2, I=20, JFLOAT=9, RM=1, TX=0\\TY=0\\TZ=0.5
REQUEST/1, F1=DX(9)\\F2=DY(9)\\F3=AZ(9)\\F4=VX(9)\\F5=VY(9)\\F6=WZ(9)\\F7=TZ(9,20)\\F8=FY(9,20)
REQUEST/2, F1=DX(20,9)\\F2=TZ(9)\\F3=DX(20)\\F4=DY(20)
END
"""


def test_measures_at_a_floating_marker_read_its_force_s_i_marker(tmp_path):
    """Trial 44's defect: DX(9), DY(9) stayed 0 and TZ(9, 20) was -0.5 - d x F. Now the
    floating marker 9 is where I (the cg 20) is: DX, DY = 0.3 t, t^2 / 4; AZ(9) = 3 t +
    t^2 / 4 (I's axes, in (-pi, pi]); VX, VY, WZ its rates; DX(20, 9) = 0; the reaction there is
    FY(9, 20) = -1 and TZ(9, 20) = TZ(9) = -0.5 (no moment arm); within 1e-8 at
    integr_tol 1e-10."""
    path = tmp_path / "pushed.adm"
    path.write_text(PUSHED_ADM)
    model = pysolver.load(path)
    assert model.markers[9].floating and model.markers[9].at == 20
    res = model.run(integr_tol=1e-10)
    assert res.success, res.message
    t, q, r = res.t, res.request(1), res.request(2)
    # AZ in (-pi, pi]
    expected = np.column_stack([0.3 * t, t * t / 4, np.angle(np.exp(1j * (3 * t + t * t / 4))),
                                0.3 + 0 * t, t / 2,
                                3 + 0.5 * t, -0.5 + 0 * t, -1 + 0 * t])
    np.testing.assert_allclose(q, expected, rtol=0, atol=1e-8)
    np.testing.assert_allclose(r[:, :2], np.column_stack([0 * t, -0.5 + 0 * t]), rtol=0,
                               atol=1e-12)
    np.testing.assert_array_equal(r[:, 2:4], q[:, :2])


PUSHED_XML = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="9" body_id="1"{floating}/>
  <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="1" inertia_yy="1" inertia_zz="1"
              v_ic_x="0.3" w_ic_z="3"/>
  <Reference_Marker id="20" body_id="2"/>
  <Force_Vector_TwoBody id="1" type="FORCEANDTORQUE" i_marker_id="20" j_floating_marker_id="9"
                        ref_marker_id="1" fx_expression="0" fy_expression="1"
                        fz_expression="0" tx_expression="0" ty_expression="0"
                        tz_expression="0.5"/>
  <Post_Request id="1" expr1="DX(9)" expr2="DY(9)" expr3="TZ(9,20)" expr4="FY(9,20)"/>
</Model><Simulate analysis_type="Transient" end_time="1" print_interval="0.01"/>
</MotionSolve>"""


@pytest.mark.parametrize("floating", [True, False])
def test_a_fixed_j_marker_keeps_its_place_and_a_floating_one_follows(floating):
    """XML: with floating="TRUE" marker 9 reads the cg's place and the reaction torque there
    is -0.5; a plain marker 9 (MotionSolve decks often name one) stays at the origin and the
    reaction about it is -T - d x F = -0.5 - 0.3 t (d = (0.3 t, t^2 / 4), F = (0, 1)); the
    motion is the same either way (the kernel applies the reaction at I's point)."""
    text = PUSHED_XML.format(floating=' floating="TRUE"' if floating else "")
    res = pysolver.loads(text).run(integr_tol=1e-10)
    assert res.success, res.message
    t, q = res.t, res.request(1)
    place = np.column_stack([0.3 * t, t * t / 4]) if floating else np.zeros((len(t), 2))
    np.testing.assert_allclose(q[:, :2], place, rtol=0, atol=1e-8)
    torque = -0.5 + 0 * t if floating else -0.5 - 0.3 * t
    np.testing.assert_allclose(q[:, 2], torque, rtol=0, atol=1e-8)
    np.testing.assert_allclose(q[:, 3], -1.0, rtol=0, atol=1e-12)


def _adm(extra, requests="REQUEST/1, F1=DX(20)"):
    return f"""floating markers
UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND
PART/1, GROUND
MARKER/1, PART=1
MARKER/9, PART=1, FLOATING
PART/2, MASS=1, CM=20, IP=1,1,1
MARKER/20, PART=2
PART/3, MASS=1, CM=30, IP=1,1,1, QG=1,0,0
MARKER/30, PART=3
{extra}
{requests}
END
"""


def test_a_floating_marker_elsewhere_is_refused(tmp_path):
    """A floating marker as a joint's J (Adams takes them on vector forces only) is a
    DeckError naming the statement and keyword."""
    path = tmp_path / "joint.adm"
    path.write_text(_adm("JOINT/1, SPHERICAL, I=20, J=9"))
    with pytest.raises(DeckError) as err:
        pysolver.load(path)
    assert str(err.value) == (
        f"{path}:10, JOINT/1 (Constraint_Joint), attribute 'J': marker 9 is FLOATING; a "
        "floating marker is the reaction marker (JFLOAT, j_floating_marker_id) of a two-body "
        "vector force only")


@pytest.mark.parametrize("statement, tag", [
    ("FIELD/1, I=20, J=9, KMATRIX=" + ",".join("100" if k % 7 == 0 else "0" for k in range(36)),
     "Force_Field"),
    ("BEAM/1, I=20, J=9, LENGTH=1, IXX=1, IYY=1, IZZ=1, AREA=1, EMODULUS=1, GMODULUS=1",
     "Force_Beam")])
def test_a_floating_marker_on_a_field_or_beam_is_refused(tmp_path, statement, tag):
    """A field's or beam's J is a fixed marker: a floating one would be read at another
    force's I marker and the element would measure nothing (review 44)."""
    path = tmp_path / "field.adm"
    path.write_text(_adm(statement))
    with pytest.raises(DeckError) as err:
        pysolver.load(path)
    assert str(err.value) == (
        f"{path}:10, {statement.split(',')[0]} ({tag}), attribute 'J': marker 9 is FLOATING; a "
        "floating marker is the reaction marker (JFLOAT, j_floating_marker_id) of a two-body "
        "vector force only")


def test_a_floating_marker_of_two_i_markers_may_not_be_read(tmp_path):
    """Two forces with I markers 20 and 30 share floating marker 9: each reaction is at its
    own I point and the deck runs, but the marker has no one place, so a request that reads
    it is a DeckError naming both forces (FX(9) too: a decision, one rule for every
    expression)."""
    forces = ("VFORCE/1, I=20, JFLOAT=9, RM=1, FX=1\\FY=0\\FZ=0\n"
              "VFORCE/2, I=30, JFLOAT=9, RM=1, FX=0\\FY=1\\FZ=0")
    path = tmp_path / "shared.adm"
    path.write_text(_adm(forces, "REQUEST/1, F1=DX(20)\\F2=DY(30)"))
    res = pysolver.load(path).run(integr_tol=1e-9)
    assert res.success and np.abs(res.request(1)[-1, :2] - 0.5).max() < 1e-8
    path.write_text(_adm(forces, "REQUEST/1, F1=FX(9)"))
    with pytest.raises(DeckError) as err:
        pysolver.load(path)
    assert str(err.value).endswith(
        "marker 9 floats with vector forces 1 (I = 20), 2 (I = 30), at more than one place, "
        "so an expression cannot read it; give each I marker its own floating marker")


def test_the_floating_flag_survives_conversion(tmp_path):
    """The dataset converted to XML has floating="TRUE" on marker 9, and back to a dataset
    FLOATING; both load the floating marker on I = 20."""
    adm = tmp_path / "pushed.adm"
    adm.write_text(PUSHED_ADM)
    xml = tmp_path / "pushed.xml"
    convert(adm, xml)
    assert 'floating="TRUE"' in xml.read_text()
    back = tmp_path / "back.adm"
    convert(xml, back)
    statements = back.read_text().replace("\n,", ",").splitlines()     # continuations joined
    assert any(line.startswith("MARKER/9,") and line.endswith(", FLOATING")
               for line in statements)
    for path in (xml, back):
        assert pysolver.load(path).markers[9].at == 20
