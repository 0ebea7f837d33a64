"""Units, case-insensitive names, command sequencing, and the progress bar."""
import io

import numpy as np
import pytest

import pysolver
from pysolver.deck.units import force_scale


@pytest.mark.parametrize("units,scale", [
    (("KILOGRAM", "METER", "SECOND", "NEWTON"), 1.0),
    (("KILOGRAM", "MILLIMETER", "SECOND", "NEWTON"), 1000.0),
    (("GRAM", "CENTIMETER", "SECOND", "DYNE"), 1.0),
    (("SLUG", "FOOT", "SECOND", "POUND_FORCE"), 1.0),
    (("MEGAGRAM", "MILLIMETER", "SECOND", "NEWTON"), 1.0),
    (("KILOGRAM", "MILLIMETER", "MILLISECOND", "KILONEWTON"), 1.0),
    (("SLINCH", "INCH", "SECOND", "POUND_FORCE"), 1.0),
    (("POUND_MASS", "FOOT", "SECOND", "POUNDAL"), 1.0),
    (("MILLIGRAM", "MILLIMETER", "SECOND", "MICRONEWTON"), 1000.0),
    (("MICROGRAM", "MICROMETER", "MICROSECOND", "NEWTON"), 1000.0),
    (("NANOGRAM", "NANOMETER", "NANOSECOND", "NANONEWTON"), 1e-6),
    (("GRAM", "CENTIMETER", "SECOND", "CENTINEWTON"), 1000.0),
    (("US_TON", "YARD", "SECOND", "MEGANEWTON"), 1e6 / (907.18474 * 0.9144)),
    (("KILOGRAM", "ANGSTROM", "DAY", "NEWTON"), 86400.0 ** 2 / 1e-10),
    (("KILOGRAM", "MILS", "SECOND", "NEWTON"), 1 / 2.54e-5),
    (("KILOGRAM", "MICROINCH", "SECOND", "NEWTON"), 1 / 2.54e-8),
])
def test_force_scale(units, scale):
    assert force_scale(*units) == pytest.approx(scale, rel=1e-12)


def test_names_are_case_insensitive():
    deck = """<motionsolve><MODEL>
      <body_rigid ID="1" IsGround="true"/>
      <REFERENCE_MARKER id="10" BODY_ID="2" Pos_Z="1"/>
      <Body_point Id="2" cg_ID="10" MASS="2"/>
      <force_gravity GRAV_Z="-10"/>
      <FORCE_PENALTY id="1" EXPR="dz(10)-1" Penalty="100"/>
      <post_request ID="1" expr1="Dz(10)"/>
      </MODEL><command><simulate ANALYSIS_TYPE="transient" END_TIME="0.1" num_step="10"/></command>
      <STOP/></motionsolve>"""
    res = pysolver.loads(deck).run()
    assert res.success and len(res.t) == 11


def test_commands_after_stop_are_ignored():
    deck = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="10" body_id="2" pos_z="1"/><Body_Point id="2" cg_id="10" mass="1"/>
      </Model>
      <Simulate analysis_type="Transient" end_time="0.5" num_step="5"/>
      <Stop/>
      <Simulate analysis_type="Transient" end_time="9" num_step="5"/>
      </MotionSolve>"""
    res = pysolver.loads(deck).run()
    assert res.t[-1] == 0.5


def test_free_fall_units_mm():
    """Free fall in mm for 0.1 s: z = z0 - g t^2 / 2 exactly (no forces but gravity)."""
    deck = """<MotionSolve><Model><Units mass="KILOGRAM" length="MILLIMETER" time="SECOND" force="NEWTON"/>
      <Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="10" body_id="2" pos_z="100"/><Body_Point id="2" cg_id="10" mass="3"/>
      <Force_Gravity grav_z="-9810"/><Post_Request id="1" expr1="DZ(10)" expr2="ACCZ(10)"/>
      </Model><Simulate analysis_type="Transient" end_time="0.1" num_step="10"/></MotionSolve>"""
    res = pysolver.loads(deck).run(integr_tol=1e-10)
    np.testing.assert_allclose(res.request(1)[:, 0], 100 - 0.5 * 9810 * res.t ** 2, atol=1e-8)
    np.testing.assert_allclose(res.request(1)[:, 1], -9810, rtol=1e-10)


def test_force_units_scale_applied_forces():
    """A 1 N constant force on 1 kg in kg/mm/s/N accelerates at 1000 mm/s^2."""
    deck = """<MotionSolve><Model><Units mass="KILOGRAM" length="MILLIMETER" time="SECOND" force="NEWTON"/>
      <Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
      <Reference_Marker id="10" body_id="2" pos_x="100"/><Body_Point id="2" cg_id="10" mass="1"/>
      <Force_Scalar_TwoBody id="1" type="Force" i_marker_id="10" j_marker_id="1" val="1"/>
      <Post_Request id="1" expr1="ACCX(10)" expr2="SFORCE(1,0,2,0)"/>
      </Model><Simulate analysis_type="Transient" end_time="0.01" num_step="2"/></MotionSolve>"""
    res = pysolver.loads(deck).run(integr_tol=1e-10)
    np.testing.assert_allclose(res.request(1)[:, :2], [[1000.0, 1.0]] * 3, rtol=1e-9)


def test_progress_bar_when_asked(decks, monkeypatch):
    err = io.StringIO()
    monkeypatch.setattr("sys.stderr", err)
    pysolver.load(decks / "catenary_bead.xml").run(progress=True)
    assert "100.0%" in err.getvalue()
    err2 = io.StringIO()
    monkeypatch.setattr("sys.stderr", err2)
    pysolver.load(decks / "catenary_bead.xml").run()   # not a terminal: silent
    assert err2.getvalue() == ""


PARAM_UNIT = """<MotionSolve><Model>
<Param_Unit force_unit="NEWTON" mass_unit="KILOGRAM" length_unit="MILLIMETER" time_unit="SECOND"/>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="10" body_id="2" pos_z="100"/>
<Body_Point id="2" cg_id="10" mass="1"/>
<Force_Gravity grav_z="-9810"/>
<Force_Vector_OneBody id="1" marker_id="10" type="FORCEONLY" fz_expression="9.81"/>
<Post_Request id="1" expr1="DZ(10)"/>
</Model><Simulate analysis_type="Transient" end_time="0.1" print_interval="0.05"/></MotionSolve>"""


def test_motionsolve_param_unit_is_the_units_element():
    """<Param_Unit mass_unit= length_unit= time_unit= force_unit=> (MotionSolve's units
    element, which MotionView writes) was an unknown element. In kg/mm/s/N a force of 9.81 N
    holds the 1 kg body against 9810 mm/s^2 (1 N = 1000 kg mm/s^2); without the force unit's
    scale it would fall 49 mm in 0.1 s."""
    model = pysolver.loads(PARAM_UNIT)
    assert model.units == {"mass": "KILOGRAM", "length": "MILLIMETER", "time": "SECOND",
                           "force": "NEWTON"}
    res = model.run()
    assert res.success and res.request(1)[-1, 0] == pytest.approx(100.0, abs=1e-9)


@pytest.mark.parametrize("old, new, attribute, words", [
    ('length_unit="MILLIMETER"', 'length_unit="FURLONG"', "length_unit",
     "unknown length unit 'FURLONG'"),
    ('time_unit="SECOND"', 'time_unit="SECOND" mass_mult_factor="0.001"', "mass_mult_factor",
     "mass_mult_factor is not supported: give the units by name"),
])
def test_param_unit_errors_name_its_own_attributes(old, new, attribute, words):
    with pytest.raises(pysolver.DeckError, match=words) as info:
        pysolver.loads(PARAM_UNIT.replace(old, new), file="pu.xml")
    assert (info.value.line, info.value.attribute) == (2, attribute)


#: A 2 kg slider on a spring of 50 (x = cos(w t), w = 5 * sqrt(UCF), UCF = one force unit in
#: mass * length / time^2), its request's channels.
SPRING_MASS = """a spring-mass
UNITS/{units}
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, REULER = 90D, 90D, 0
PART/2, MASS = 2, CM = 20, IP = 1, 1, 1, QG = 1, 0, 0
MARKER/20, PART = 2
MARKER/21, PART = 2, REULER = 90D, 90D, 0
JOINT/1, TRANSLATIONAL, I = 21, J = 2
SPRINGDAMPER/1, TRANSLATIONAL, I = 20, J = 1, K = 50, C = 0, LENGTH = 0
REQUEST/1, F1 = DX(20)\\F2 = VX(20)\\
END
"""


@pytest.mark.parametrize("units, ucf, length, speed", [
    ("FORCE = POUND_FORCE, MASS = SLINCH, LENGTH = INCH, TIME = SECOND", 1.0, "in", "in/s"),
    ("FORCE = POUNDAL, MASS = POUND_MASS, LENGTH = FOOT, TIME = SECOND", 1.0, "ft", "ft/s"),
    ("FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = MILLISECONDS", 1e-6, "m",
     "m/ms"),
    ("FORCE = MICRONEWTON, MASS = MILLIGRAM, LENGTH = MICROMETER, TIME = SECOND", 1e6,
     "um", "um/s"),
    ("FORCE = CENTINEWTON, MASS = US_TON, LENGTH = YARD, TIME = MINUTE",
     0.01 / (907.18474 * 0.9144 / 60 ** 2), "yd", "yd/min"),
    ("FORCE = NANONEWTON, MASS = NANOGRAM, LENGTH = MILS, TIME = MICROSECOND",
     1e-9 / (1e-12 * 2.54e-5 / 1e-6 ** 2), "mil", "mil/us"),
    ("SYSTEM = NONE", 1.0, "m", "m/s"),
])
def test_adams_unit_names_give_the_spring_mass_its_frequency(tmp_path, units, ucf, length,
                                                             speed):
    """Adams Solver's UNITS names pysolver read as unknown (SLINCH, POUNDAL, MILLISECONDS,
    MICRONEWTON, MILLIGRAM, MICROMETER, CENTINEWTON, US_TON, YARD, NANONEWTON, NANOGRAM,
    MILS, MICROSECOND; SYSTEM = NONE, nondimensional, read as a dataset without UNITS):
    over one period x = cos(w t) to 1e-6 with w = 5 sqrt(UCF), the UCF from the units' SI
    values written here; the channels are labelled in the deck's units."""
    path = tmp_path / "sm.adm"
    path.write_text(SPRING_MASS.format(units=units))
    omega = 5.0 * np.sqrt(ucf)
    model = pysolver.load(path, simulate={"analysis_type": "TRANSIENT",
                                          "end_time": 2 * np.pi / omega, "num_step": 40})
    assert model.force_scale == pytest.approx(ucf, rel=1e-14)
    res = model.run(integr_tol=1e-9)
    assert res.success and len(res.t) == 41
    np.testing.assert_allclose(res.request(1)[:, 0], np.cos(omega * res.t), rtol=0, atol=1e-6)
    assert (res.units["REQ1.1"], res.units["REQ1.2"]) == (length, speed)


def test_system_none_takes_no_other_units(tmp_path):
    path = tmp_path / "none.adm"
    path.write_text(SPRING_MASS.format(units="SYSTEM = NONE, LENGTH = MM"))
    with pytest.raises(pysolver.DeckError) as info:
        pysolver.load(path)
    assert (info.value.line, info.value.attribute, info.value.reason) == (
        2, "LENGTH", "LENGTH is not supported: SYSTEM=NONE is a nondimensional dataset")


@pytest.mark.parametrize("spelling, name", [("KNewton", "KILONEWTON"), ("Tonne", "MEGAGRAM"),
                                            ("Mills", "MILS"), ("MilliInch", "MILS"),
                                            ("US Ton", "US_TON"),
                                            ("Milliseconds", "MILLISECOND")])
def test_motionsolve_spellings_of_units(spelling, name):
    """The names of MotionSolve's Units and Param_Unit pages that differ from pysolver's."""
    kind = {"KILONEWTON": "force", "MEGAGRAM": "mass", "US_TON": "mass",
            "MILLISECOND": "time"}.get(name, "length")
    deck = f'''<MotionSolve><Model><Units {kind}="{spelling}"/>
      <Body_Rigid id="1" isground="TRUE"/></Model></MotionSolve>'''
    assert pysolver.loads(deck).units[kind] == name
