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
