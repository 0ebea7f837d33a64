"""Every output carries its unit: request channels typed from their expressions
(pysolver/deck/dimensions.py), CSV headers saved and streamed, DataFrames, Result.units and
quantities, LoadControl records."""
import pathlib

import numpy as np
import pytest

import pysolver
from pysolver.deck import dimensions, expr

DECKS = pathlib.Path(__file__).resolve().parent.parent / "decks"
README_HEADER = "time [s],x [mm],z [mm],force_L1 [N],force_L2 [N]"


@pytest.fixture(scope="module")
def particle():
    return pysolver.load(DECKS / "particle_between_lines.xml")


def _unit(model, text):
    return dimensions.quantity(dimensions.Typer(model).of(expr.parse(text)), model.units)


@pytest.mark.parametrize("text, unit, kind", [
    ("DX(10)", "mm", "length"), ("DM(10)", "mm", "length"), ("VZ(10)", "mm/s", "velocity"),
    ("VR(10, 1)", "mm/s", "velocity"), ("ACCX(10)", "mm/s^2", "acceleration"),
    ("WZ(10)", "rad/s", "angular velocity"), ("WDTX(10)", "rad/s^2", "angular acceleration"),
    ("PSI(10)", "rad", "angle"), ("AZ(10)", "rad", "angle"), ("YAW(10)", "rad", "angle"),
    ("ATAN2(DZ(10), DX(10))", "rad", "angle"), ("PFORCE(1)", "N", "force"),
    ("FZ(10)", "N", "force"), ("TX(10)", "N*mm", "torque"), ("KE(0)", "N*mm", "energy"),
    ("TIME", "s", "time"), ("2.5", "-", "dimensionless"), ("COS(WZ(10)*TIME)", "-",
                                                            "dimensionless"),
    ("1+DX(10)-DZ(10)", "mm", "length"), ("-DZ(10)", "mm", "length"),
    ("DX(10)/TIME", "mm/s", "velocity"), ("ACCZ(10)*TIME**2", "mm", "length"),
    ("SQRT(DX(10)**2 + DZ(10)**2)", "mm", "length"), ("PFORCE(1)*DX(10)", "N*mm", "torque"),
    ("PFORCE(1)/DX(10)", "N/mm", None), ("1/TIME", "1/s", None),
    ("RTOD*AZ(10)", "deg", "angle"), ("MAX(DZ(10), 0)", "mm", "length"),
    ("IF(TIME-1: DX(10), 0, DZ(10))", "mm", "length"), ("5*SIN(TIME) + DX(10)", "mm", "length"),
    ("STEP(TIME, 0, 0, 1, PFORCE(1))", "N", "force"), ("ABS(VX(10))", "mm/s", "velocity"),
])
def test_an_expression_has_the_unit_of_what_it_measures(particle, text, unit, kind):
    assert _unit(particle, text) == (unit, kind)


@pytest.mark.parametrize("text, unit", [
    ("SPDP(1, 0, 2, 0)", "N"), ("SPDP(2, 0, 8, 0)", "N*m"), ("JOINT(1, 0, 1, 0)", "N"),
    ("JOINT(1, 1, 5, 0)", "N*m"), ("SFORCE(6, 0, 3, 0)", "N"), ("SFORCE(7, 0, 7, 0)", "N*m")])
def test_element_forces_are_forces_or_torques_by_component(text, unit):
    model = pysolver.load(pathlib.Path(__file__).parent / "decks" / "springs.xml")
    assert _unit(model, text) == (unit, "force" if unit == "N" else "torque")


@pytest.mark.parametrize("text", ["DX(10) + VX(10)", "DY(10) - COSH(DX(10))",
                                  "IF(TIME-1: DX(10), 0, VX(10))", "DX(10)**TIME",
                                  "MIN(TIME, DZ(10))"])
def test_terms_that_do_not_match_have_no_unit(particle, text):
    assert _unit(particle, text) == (None, None)


def test_variables_are_typed_through_their_expressions():
    text = (DECKS / "particle_between_lines.xml").read_text().replace(
        'end_time="3.0"', 'end_time="0.01"').replace(
        '<Post_Request id="1"',
        '<Reference_Variable id="5" expr="VZ(10)*2"/>\n'
        '    <Reference_Variable id="6" expr="VARVAL(5) + DX(10)"/>\n'
        '    <Post_Request id="2" expr1="VARVAL(5)" expr2="VARVAL(6)" name1="v2" name2="mix"/>\n'
        '    <Post_Request id="1"')
    res = pysolver.loads(text).run()
    assert res.units["v2"] == "mm/s" and res.units["mix"] is None
    assert res.quantities["v2"] == "velocity" and res.quantities["mix"] is None


def test_a_deck_without_units_is_labelled_in_si():
    """No Units element: the loader's units, kg/m/s/N (docs/usage.md, Units)."""
    res = pysolver.load(DECKS / "catenary_bead.xml").run()
    names, _ = res.columns(units=True)
    assert names == ["time [s]", "x [m]", "y [m]", "vx [m/s]", "vy [m/s]", "g",
                     "penalty_force [N]"]
    assert res.units["g"] is None


def test_the_readme_deck_csv_header_saved_and_streamed(particle, tmp_path):
    res = particle.run(stream=tmp_path / "streamed.csv")
    res.save(tmp_path / "saved.csv")
    for name in ("streamed.csv", "saved.csv"):
        assert (tmp_path / name).read_text().splitlines()[0] == README_HEADER
    assert (tmp_path / "streamed.csv").read_bytes() == (tmp_path / "saved.csv").read_bytes()
    assert res.columns()[0] == ["time", "x", "z", "force_L1", "force_L2"]   # bare by default
    assert res.units == {"time": "s", "x": "mm", "z": "mm", "force_L1": "N", "force_L2": "N"}
    assert res.quantities == {"time": "time", "x": "length", "z": "length",
                              "force_L1": "force", "force_L2": "force"}


def test_the_npz_holds_the_csv_table_with_its_units(particle, tmp_path):
    res = particle.run()
    res.save(tmp_path / "r.npz")
    with np.load(tmp_path / "r.npz") as npz:
        assert ",".join(npz["table_columns"]) == README_HEADER
        np.testing.assert_array_equal(npz["table"], res.columns()[1])
        np.testing.assert_array_equal(npz["request_1"][:, :4], res.request(1)[:, :4])


def test_dataframe_columns_carry_units_and_attrs_map_bare_names(particle):
    pytest.importorskip("pandas", reason="pandas is not installed")
    res = particle.run()
    df = res.to_dataframe()
    assert list(df.columns) == ["x [mm]", "z [mm]", "force_L1 [N]", "force_L2 [N]"]
    assert df.index.name == "time [s]"
    assert df.attrs["units"] == res.units and df.attrs["quantities"] == res.quantities
    np.testing.assert_array_equal(df["z [mm]"].to_numpy(), res.request(1)[:, 1])


def test_typed_requests_have_per_channel_units():
    text = (DECKS / "torque_free_spin.xml").read_text().replace(
        'end_time="2.0"', 'end_time="0.01"').replace('<Post_Request id="1"',
        '<Post_Request id="2" type="MARKER_DISPLACEMENT" i_marker_id="20"/>\n'
        '    <Post_Request id="3" type="MARKER_VELOCITY" i_marker_id="20"/>\n'
        '    <Post_Request id="4" type="MARKER_ACCELERATION" i_marker_id="20"/>\n'
        '    <Post_Request id="1"')
    res = pysolver.loads(text).run()
    names, _ = res.columns(units=True)
    for expected in ("mag [m]", "y [m]", "psi [rad]", "theta [rad]", "phi [rad]",
                     "vm [m/s]", "vz [m/s]", "wm [rad/s]", "wy (request 3) [rad/s]",
                     "accm [m/s^2]",
                     "accx [m/s^2]", "wdtm [rad/s^2]", "wdtz [rad/s^2]"):
        assert expected in names


def test_loadcontrol_records_carry_units(tmp_path):
    res = pysolver.load(DECKS / "loadcontrol_indenter.xml").run()
    res.save(tmp_path / "r.csv")
    header = (tmp_path / "r_controller1.csv").read_text().splitlines()[0]
    assert header == ("time [s],target [N],measured [N],filtered [N],displacement [mm],"
                      "A [N/mm],e [mm],Ie [mm],De [mm],velocity [mm/s],clamped")
    assert res.controller_units()["velocity"] == "mm/s"


def test_meta_keeps_each_commands_end_time():
    res = pysolver.load(DECKS / "static_seed3.xml").run()
    assert res.meta["commands"] == [{"analysis": "STATIC", "end_time": 0.0},
                                    {"analysis": "TRANSIENT", "end_time": 0.1}]


@pytest.mark.parametrize("text, unit, kind", [
    ("AZ(10)*180/PI", "deg", "angle"), ("AZ(10)*(180/PI)", "deg", "angle"),
    ("-AZ(10)*180/PI", "deg", "angle"), ("57.29578*AZ(10)", "deg", "angle"),
    ("57.2958*AZ(10)", "deg", "angle"), ("AZ(10)/DTOR", "deg", "angle"),
    ("AZ(10)*1/DTOR", "deg", "angle"), ("AZ(10)*RTOD*2", "deg", "angle"),
    ("WZ(10)*180/PI", "deg/s", "angular velocity"),
    ("57.29578*WDTZ(10)", "deg/s^2", "angular acceleration"),
    ("RTOD*AZ(10)*PI/180", "rad", "angle"), ("RTOD*AZ(10)*0.0174532925", "rad", "angle"),
])
def test_a_written_180_over_pi_converts_to_degrees(particle, text, unit, kind):
    """180/PI, 1/DTOR and numbers within 1e-6 of 57.29578 are RTOD; PI/180 is DTOR."""
    assert _unit(particle, text) == (unit, kind)


@pytest.mark.parametrize("text, unit, kind", [
    ("-DX(10)", "mm", "length"), ("2*DX(10)", "mm", "length"), ("DX(10)*-1", "mm", "length"),
    ("(DX(10)+DZ(10))/2", "mm", "length"), ("0.5*KE(0)", "N*mm", "energy"),
    ("0.5*VM(10)**2", "mm^2/s^2", None), ("4/3*PI*DM(10)**3", "mm^3", None),
    ("2*PI*DX(10)", "mm", "length"), ("DX(10)/3", "mm", "length"),
    ("9*DX(10)", "mm", "length"), ("DX(10)*2**2", "mm", "length"), ("2/TIME", "1/s", None),
    ("RTOD*AZ(10)", "deg", "angle"), ("KE(0)", "N*mm", "energy"),
    ("DX(10)/DM(10)*100", "-", "dimensionless"), ("180/PI", "-", "dimensionless"),
])
def test_plain_factors_keep_the_unit(particle, text, unit, kind):
    assert _unit(particle, text) == (unit, kind)


@pytest.mark.parametrize("text", [
    "1000*DX(10)", "DX(10)/1000", "0.1*DX(10)", "10*DX(10)", "1.7*VM(10)**2",
    "WZ(10)*30/PI", "WZ(10)/(2*PI)", "PI*AZ(10)", "57.296*AZ(10)", "AZ(10)*180",
    "DX(10)*2**10", "1000*DX(10) + DZ(10)", "1e-3*PFORCE(1)",
])
def test_other_written_factors_leave_no_unit(particle, text):
    """A number that may be a unit conversion or a constant with units (a mass, a
    stiffness) would make the kept unit wrong: docs/usage.md, Units."""
    assert _unit(particle, text) == (None, None)


DEG_DECK = """<?xml version="1.0"?>
<MotionSolve>
  <Model>
    <Units mass="KILOGRAM" length="METER" time="SECOND" force="NEWTON"/>
    <Body_Rigid id="1" isground="TRUE"/>
    <Reference_Marker id="2" body_id="1"/>
    <Reference_Marker id="20" body_id="2" pos_x="2"/>
    <Reference_Marker id="21" body_id="2"/>
    <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1e-3" inertia_yy="1e-3"
                inertia_zz="1e-3"/>
    <Force_Gravity grav_y="-9.81"/>
    <Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="2"/>
    <Post_Request id="1" expr1="AZ(20)" expr2="AZ(20)*180/PI" expr3="57.29578*AZ(20)"
                  expr4="RTOD*AZ(20)" expr5="1000*DX(20)" expr6="WZ(20)*180/PI"
                  name1="a_rad" name2="a_180_over_pi" name3="a_5729" name4="a_rtod"
                  name5="x_mm" name6="w_deg"/>
  </Model>
  <Simulate analysis_type="Transient" end_time="1" print_interval="0.25"/>
</MotionSolve>
"""


def test_degree_channels_are_labelled_deg_in_csv_units_and_plot(tmp_path):
    """Trial 44, defect 1: the two degree channels were `[rad]` and shared the radian
    panel."""
    res = pysolver.loads(DEG_DECK).run()
    res.save(tmp_path / "r.csv")
    assert (tmp_path / "r.csv").read_text().splitlines()[0] == (
        "time [s],a_rad [rad],a_180_over_pi [deg],a_5729 [deg],a_rtod [deg],x_mm,"
        "w_deg [deg/s]")
    assert res.units == {"time": "s", "a_rad": "rad", "a_180_over_pi": "deg",
                         "a_5729": "deg", "a_rtod": "deg", "x_mm": None, "w_deg": "deg/s"}
    np.testing.assert_allclose(res.request(1)[:, 1], res.request(1)[:, 3], rtol=1e-15)
    np.testing.assert_allclose(res.request(1)[:, 2], res.request(1)[:, 3], rtol=1e-7)
    pytest.importorskip("matplotlib", reason="matplotlib is not installed")
    fig = res.plot()
    panels = {ax.get_ylabel(): [t.get_text() for t in ax.get_legend().get_texts()]
              for ax in fig.axes if ax.get_legend()}
    assert panels["angle [rad]"] == ["a_rad"]
    assert panels["angle [deg]"] == ["a_180_over_pi", "a_5729", "a_rtod"]
    assert panels["angular velocity [deg/s]"] == ["w_deg"]
    assert panels["no unit"] == ["x_mm"]


PENDULUM = """<?xml version="1.0"?>
<MotionSolve>
  <Model>
    <Units mass="KILOGRAM" length="{length}" time="{time}" force="NEWTON"/>
    <Body_Rigid id="1" isground="TRUE"/>
    <Reference_Marker id="2" body_id="1"/>
    <Reference_Marker id="20" body_id="2" pos_x="{arm}"/>
    <Reference_Marker id="21" body_id="2"/>
    <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="{inertia}" inertia_yy="{inertia}"
                inertia_zz="{inertia}"/>
    <Force_Gravity grav_y="{g}"/>
    <Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="2"/>
    <Reference_Marker id="3" body_id="1" pos_x="{sx}" pos_y="{sy}"/>
    <Force_SpringDamper id="1" type="TRANSLATIONAL" i_marker_id="20" j_marker_id="3"
                        stiffness="0" damping="0" length="{sy}"/>
    <Post_Request id="1" expr1="AZ(20)" name1="angle"/>
  </Model>
  <Simulate analysis_type="Transient" end_time="{end}" print_interval="{step}"/>
</MotionSolve>
"""
SI = dict(length="METER", time="SECOND", arm=2, inertia=1e-3, g=-9.81, end=2, step=0.02,
          sx=1, sy=0.5)
MM_MS = dict(length="MILLIMETER", time="MILLISECOND", arm=2000, inertia=1000, g=-9.81e-3,
             end=2000, step=20, sx=1000, sy=500)


def test_integr_tol_is_absolute_in_the_decks_units():
    """The figures of docs/deck-language.md, "integr_tol is absolute in the deck's units"
    (trial 44, defect 7): the trial's pendulum (its spring at stiffness 0) in kg/m/s and in
    kg/mm/ms (its angular velocity about 1e-3 rad/ms), against the SI deck at 1e-10; forces
    are in N in both. At a loose tolerance one run's error depends on its step sequence
    (0.11-0.85 % of the peak in SI between integr_tol 0.9e-3 and 1.1e-3), so the claim is on
    the median over five tolerances about the default."""
    ref = pysolver.loads(PENDULUM.format(**SI)).run(integr_tol=1e-10)
    peak = np.max(ref.joint(1)[:, 0])
    loose, tight = {}, {}
    for name, units in (("si", SI), ("mm_ms", MM_MS)):
        model = pysolver.loads(PENDULUM.format(**units))

        def errors(tol, model=model):
            res = model.run(integr_tol=tol)
            return (np.max(np.abs(res.joint(1)[:, 0] - ref.joint(1)[:, 0])) / peak,
                    # AZ is in (-pi, pi], and the pendulum swings to -pi: the wrapped difference
                    np.max(np.abs(np.angle(np.exp(1j * (res.request(1)[:, 0]
                                                        - ref.request(1)[:, 0]))))))
        loose[name] = np.median([errors(tol) for tol in (0.9e-3, 0.95e-3, 1e-3, 1.05e-3,
                                                         1.1e-3)], axis=0)
        tight[name] = errors(1e-6)
    # the force: 0.21 % of its peak in SI, 0.88 % in kg/mm/ms
    assert loose["si"][0] < 0.005 < loose["mm_ms"][0] < 0.02
    assert loose["mm_ms"][0] > 2.5 * loose["si"][0]
    for name in ("si", "mm_ms"):
        assert tight[name][0] < 1e-4 and tight[name][1] < 1e-4
