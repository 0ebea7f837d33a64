"""Adams datasets (.adm) and command files (.acf): a dataset of every statement pysolver reads
against the same model written by hand as XML, the lexical rules, the commands, conversion to
XML, and bad input."""
import shutil
import warnings

import numpy as np
import pytest

import pysolver
from pysolver import DeckError, DeckWarning
from pysolver.cli import main

from helpers import DECKS, TEST_DECKS

ADAMS = TEST_DECKS / "adams"


def _load(path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeckWarning)
        return pysolver.load(path, **kw)


def _rel(a, b):
    """Largest difference of two request tables over each channel's largest value (>= 1)."""
    assert np.array_equal(np.isnan(a), np.isnan(b))        # the same unused channels
    used = ~np.all(np.isnan(b), axis=0)
    a, b = a[:, used], b[:, used]
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b).max(axis=0))))


def test_every_statement_builds_the_model_written_by_hand_in_xml():
    """Markers at their global places from part frames (QG/REULER, XG/ZG), part-relative
    QP/REULER in degrees, ZP/XP and an RM chain; inertia; equal to the hand-written XML to
    1e-12 (relative to the model's size)."""
    a, x = _load(ADAMS / "every_statement.adm"), _load(ADAMS / "every_statement.xml")
    assert sorted(a.markers) == sorted(x.markers)
    for mid, m in x.markers.items():
        assert a.markers[mid].body == m.body
        assert np.abs(a.markers[mid].pos - m.pos).max() <= 1e-12 * 600, mid
        assert np.abs(a.markers[mid].rot - m.rot).max() <= 1e-12, mid
    for bid, b in x.bodies.items():
        assert a.bodies[bid].kind == b.kind and a.bodies[bid].mass == b.mass
        if b.inertia is not None:
            assert np.abs(a.bodies[bid].inertia - b.inertia).max() <= 1e-12 * 4000
            np.testing.assert_allclose(a.bodies[bid].omega, b.omega, atol=1e-12)
            np.testing.assert_allclose(a.bodies[bid].vel, b.vel, atol=1e-12)
    for table in ("joints", "motions", "gcons", "couplers", "scalar_forces", "vector_forces",
                  "bushings", "variables", "splines", "sensors", "requests"):
        if hasattr(x, table):
            assert sorted(getattr(a, table)) == sorted(getattr(x, table)), table
    assert [c.end_time for c in a.commands] == [c.end_time for c in x.commands] == [1.0]


def test_every_statement_runs_as_its_xml_translation_to_the_integration_error():
    """Both forms halt at the sensor (t = 0.8) with every request channel equal to 1e-9 of
    its scale at integr_tol 1e-11 (measured 1.3e-10; the two differ by rounding in the last
    bit of their inputs, so their steps differ within the tolerance)."""
    a, x = _load(ADAMS / "every_statement.adm"), _load(ADAMS / "every_statement.xml")
    ra, rx = a.run(integr_tol=1e-11), x.run(integr_tol=1e-11)
    assert ra.success and rx.success, (ra.message, rx.message)
    assert ra.t[-1] == rx.t[-1] == pytest.approx(0.8)
    assert any("Sensor_Event 1 fired" in line for line in ra.log)
    for rid in range(1, 6):
        assert _rel(ra.request(rid), rx.request(rid)) <= 1e-9, rid
    # the coupler turns the wheel (joint 4) by half the crank's driven angle
    az_crank = 2 * ra.t + 0.1 * np.sin(3 * ra.t)
    np.testing.assert_allclose(np.unwrap(ra.request(5)[:, 3]), az_crank / 2, atol=1e-8)


def test_convert_writes_the_xml_that_runs_identically(tmp_path):
    """pysolver convert: the XML it writes builds the same elements, so its run equals the
    dataset's bit for bit."""
    out = tmp_path / "every.xml"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeckWarning)
        assert main(["convert", str(ADAMS / "every_statement.adm"), "-o", str(out)]) == 0
    ra = _load(ADAMS / "every_statement.adm").run()
    rc = _load(out).run()
    for rid in range(1, 6):
        np.testing.assert_array_equal(ra.request(rid), rc.request(rid))
    assert "<Simulate" in out.read_text() and "num_step=\"100\"" in out.read_text()


def test_commands_from_the_command_file(tmp_path):
    """The .acf beside the dataset gives its commands (here 1 s, 100 steps, ERROR=1e-8);
    loading the .acf does the same; alone, the dataset gets the default command; the command
    line's --end and --steps replace them."""
    beside = _load(ADAMS / "every_statement.adm")
    direct = _load(ADAMS / "every_statement.acf")
    for m in (beside, direct):
        assert [(c.analysis, c.end_time, c.print_interval) for c in m.commands] == \
            [("TRANSIENT", 1.0, 0.01)]
        assert m.transient.integr_tol == 1e-8
    alone = tmp_path / "alone.adm"
    shutil.copy(ADAMS / "every_statement.adm", alone)
    default = pysolver.loads('<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>'
                             '</Model></MotionSolve>')
    assert [(c.end_time, c.print_interval) for c in _load(alone).commands] == \
        [(c.end_time, c.print_interval) for c in default.commands]
    cli = _load(alone, simulate={"analysis_type": "TRANSIENT", "end_time": 0.3,
                                 "num_step": 3})
    assert [(c.end_time, c.print_interval) for c in cli.commands] == [(0.3, pytest.approx(0.1))]


def test_the_lexical_rules(tmp_path):
    """Comments, continuation lines (inside a function too), abbreviated statement and
    keyword names, D for degrees in numbers and in functions, backslash-separated functions,
    a function ended by a comma, leading zeros in ids, the view name as a label."""
    text = """a title line that is not read: PART/1, MASS=oops
! adams_view_name='the ground'
PART/001, GROUND   ! a comment
MARK/1, PART = 1
MARKER/2, PART = 1, QP = 0, 0, 0,
, REU = 90D, 0,
, 0
PA/2, MASS = 1, CM = 3, IP = 1, 1, 1, QG = 1, 0, 0
MARKER/3, PART = 2
ACC/JGRAV = -9.81
REQUEST/1, F1 = STEP(TIME, 0, 0,
, 1, 90D)\\F2 = 2 *
, DX(3)\\, F3 = AX(2), COMMENT = after a function ended by a comma
SENSOR/1, FUNCTION = TIME, VALUE = 0.5, GE, HALT
END
PART/9, this is after END and is not read
text after END that is no statement at all (it stopped the load)
, nor a continuation
"""
    path = tmp_path / "lex.adm"
    path.write_text(text)
    m = _load(path)
    assert m.bodies[1].label == "the ground"
    np.testing.assert_allclose(m.markers[2].rot, [[0, -1, 0], [1, 0, 0], [0, 0, 1]],
                               atol=1e-15)
    res = m.run()
    assert res.success and res.t[-1] == pytest.approx(0.5)
    q = res.request(1)
    np.testing.assert_allclose(q[:, 0], np.pi / 2 * np.clip(res.t, 0, 1) ** 2
                               * (3 - 2 * np.clip(res.t, 0, 1)), atol=1e-12)
    np.testing.assert_allclose(q[:, 1], 2.0, atol=1e-12)       # the body falls along y


@pytest.mark.parametrize("stmt, words, attribute", [
    ("MARKER/5, PART = 2, QP = 0, 0", "QP takes three numbers", "QP"),
    ("MARKER/5, PART = 2, QPP = 0, 0, 0", "unknown keyword QPP; did you mean QP?", "QPP"),
    ("MARKER/5, PART = 7", "part 7 does not exist", "PART"),
    ("MARKER/5, PART = 2, R = 1", "R is ambiguous: it abbreviates REULER, RM", "R"),
    ("CONTACT/1, I = 3, J = 1", "CONTACT is not supported by pysolver", None),
    ("SFORCE/1, I = 3, J = 1, TRANSLATION, FUNCTION = 1 +", "bad expression", "FUNCTION"),
    ("PART/5, MASS = 2x, CM = 3", "got '2x'; expected a real number", "MASS"),
    ("JOINT/1, I = 3, J = 1", "give one of CONVEL", None),
    ("FOO/1, BAR = 2", "unknown statement FOO", None),
    ("MOTOIN/1, JOINT = 1", "unknown statement MOTOIN; did you mean MOTION", None),
    # cut short: a keyword with no value, a function with no end
    ("PART/5, MASS =", "MASS = has no value", "MASS"),
    ("REQUEST/1, F1 = DX(3", r"bad expression 'DX\(3': expected '\)'", "F1"),
    # pysolver's extensions are checked as Adams' statements are
    ("PFORCE/1, FUNCTION = DZ(3)\\, PENALTY = 1, UNILATERL",
     "unknown keyword UNILATERL; did you mean UNILATERAL?", "UNILATERL"),
])
def test_bad_statements_are_deck_errors_naming_file_line_and_statement(tmp_path, stmt, words,
                                                                     attribute):
    path = tmp_path / "bad.adm"
    path.write_text("title\nPART/1, GROUND\nMARKER/1, PART = 1\nPART/2, MASS = 1, CM = 3, "
                    f"IP = 1, 1, 1\nMARKER/3, PART = 2\n{stmt}\nEND\n")
    with pytest.raises(DeckError, match=words) as err:
        _load(path)
    assert err.value.file == str(path) and err.value.line == 6
    assert err.value.element.split(" ")[0] == stmt.split(",")[0]       # MARKER/5, FOO
    if attribute:
        assert err.value.attribute == attribute


RM_RULE = ("Adams requires the RM marker on the marker's own part (give QP and the axes in "
           "{part}'s frame, or an RM of {part})")


def test_an_rm_on_another_part_is_a_deck_error(tmp_path):
    """Adams' RM is a marker of the same part (docs/adams.md, "Placement"); a dataset whose RM
    was on another part was read with QP in that marker's frame (trial 43, item 2). It is a
    DeckError naming the file, RM's line, the marker and RM, for a part's marker and a point
    mass's, and for a msolve class Marker's rm (at the script's line); an RM marker without
    a part names that marker (it was a KeyError)."""
    head = "rm on another part\nPART/1, GROUND\nMARKER/2, PART=1, QP=1, 0, 0, REULER=90D, 0, 0\n"
    path = tmp_path / "rm.adm"
    path.write_text(head + "PART/2, MASS=1, CM=20, IP=1, 1, 1, QG=0, 5, 0, REULER=0, 90D, 0\n"
                    "MARKER/20, PART=2, QP=1, 0, 0, RM=2\nEND\n")
    with pytest.raises(DeckError) as err:
        _load(path)
    assert str(err.value) == f"{path}:5, MARKER/20, attribute 'RM': RM = 2 is a marker of " \
        "PART/1, not of PART/2: " + RM_RULE.format(part="PART/2")
    path.write_text(head + "PART/2, MASS=1, CM=20, IP=1, 1, 1\nMARKER/20, PART=2\n"
                    "POINT_MASS/3, MASS=1, CM=30\nMARKER/30, POINT_MASS=3,\n, RM=20\nEND\n")
    with pytest.raises(DeckError) as err:
        _load(path)
    assert str(err.value) == f"{path}:8, MARKER/30, attribute 'RM': RM = 20 is a marker of " \
        "PART/2, not of POINT_MASS/3: " + RM_RULE.format(part="POINT_MASS/3")
    path.write_text(head + "PART/2, MASS=1, CM=20, IP=1, 1, 1\nMARKER/20, PART=2, RM=21\n"
                    "MARKER/21, QP=1, 0, 0\nEND\n")
    with pytest.raises(DeckError) as err:
        _load(path)
    assert str(err.value) == f"{path}:6, MARKER/21: a marker needs PART= (or POINT_MASS=)"
    script = tmp_path / "classes.py"
    script.write_text("from pysolver.msolve import *\nmodel = Model()\n"
                      "ground = Part(ground=True)\nrm = Marker(body=ground, qp=[1, 0, 0])\n"
                      "arm = Part(mass=1, ip=[1, 1, 1])\n"
                      "arm.cm = Marker(body=arm, qp=[1, 0, 0], rm=rm)\n")
    with pytest.raises(DeckError) as err:
        _load(script)
    assert str(err.value) == f"{script}:6, MARKER/2, attribute 'RM': RM = 1 is a marker of " \
        "PART/1, not of PART/2: " + RM_RULE.format(part="PART/2")


def test_an_rm_on_the_same_part_places_the_marker_in_its_frame(tmp_path):
    """RM on the marker's own part (a moved part): QP, REULER in RM's frame."""
    path = tmp_path / "rm.adm"
    path.write_text("same part\nPART/1, GROUND\nMARKER/1, PART=1\n"
                    "PART/2, MASS=1, CM=20, IP=1, 1, 1, QG=0, 5, 0, REULER=90D, 0, 0\n"
                    "MARKER/21, PART=2, QP=1, 0, 0, REULER=90D, 0, 0\n"
                    "MARKER/20, PART=2, QP=1, 0, 0, RM=21\nEND\n")
    m = _load(path)
    np.testing.assert_allclose(m.markers[21].pos, [0, 6, 0], atol=1e-15)
    np.testing.assert_allclose(m.markers[20].pos, [-1, 6, 0], atol=1e-15)
    np.testing.assert_allclose(m.markers[20].rot, [[-1, 0, 0], [0, -1, 0], [0, 0, 1]],
                               atol=1e-15)


def test_an_xml_file_holding_a_dataset_says_so(tmp_path):
    path = tmp_path / "model.xml"
    path.write_text("title\nPART/1, GROUND\nMARKER/1, PART = 1\nEND\n")
    with pytest.raises(DeckError, match="not XML: the file reads as an Adams dataset .*; "
                                        "name it .adm") as err:
        pysolver.load(path)
    assert (err.value.file, err.value.line) == (str(path), 1)


def test_a_file_in_no_known_format_says_which_formats_exist(tmp_path):
    path = tmp_path / "model.dat"
    path.write_text("some notes\nnot a deck\n")
    with pytest.raises(DeckError, match="expected MotionSolve XML .* an Adams dataset"):
        pysolver.load(path)
    path.write_text("title\nPART/1, GROUND\nMARKER/1, PART = 1\nEND\n")
    assert pysolver.load(path).source.fmt == "adm"      # a dataset under another name


def test_a_command_file_naming_a_missing_dataset(tmp_path):
    acf = tmp_path / "run.acf"
    acf.write_text("nowhere\nout\nSIMULATE/DYNAMICS, END = 1, STEPS = 10\nSTOP\n")
    with pytest.raises(DeckError, match="nowhere.adm named on the first line does not exist"):
        pysolver.load(acf)


def test_the_command_line_runs_a_dataset_for_the_time_it_is_told(tmp_path, capsys):
    """pysolver run model.adm --end 0.2 --steps 4: five rows from 0 to 0.2, in place of the
    command file's 1 s; --steps without --end is a usage error (exit 2)."""
    out = tmp_path / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeckWarning)
        assert main(["run", str(ADAMS / "every_statement.adm"), "--end", "0.2", "--steps", "4",
                     "-q", "--no-plot", "-o", str(out)]) == 0
    rows = (out / "requests.csv").read_text().splitlines()
    assert len(rows) == 6 and rows[-1].startswith("0.2")
    assert main(["run", str(ADAMS / "every_statement.adm"), "--steps", "4"]) == 2
    assert capsys.readouterr().err == "pysolver: error: --steps and --dtout need --end\n"


def test_spellings_adams_accepts(tmp_path):
    """TRANSLATIONAL/ROTATIONAL for TRANSLATION/ROTATION, D V A F and C (COMMENT, also a
    prefix of CNAMES) on REQUEST (V is also a prefix of VARIABLES), GRAPHICS with any
    keyword, & continuing a command."""
    path = tmp_path / "s.adm"
    path.write_text("title\nPART/1, GROUND\nMARKER/1, PART = 1\nMARKER/2, PART = 1\n"
                    "PART/2, MASS = 1, CM = 3, IP = 1, 1, 1\nMARKER/3, PART = 2\n"
                    "SFORCE/1, ROTATIONAL, I = 3, J = 2, FUNCTION = 2\n"
                    "REQUEST/1, V, I = 3, C = velocity: x y z\nREQUEST/2, A, I = 3\n"
                    "GRAPHICS/1, CYLINDER, CM = 3, RANGLE = 360, ANYTHING = 2\n"
                    "GRAPHICS/2, BOX, CORNER = 3, X = 0.2, Y = .2, Z = 4\nEND\n")
    (tmp_path / "s.acf").write_text("s\n\nsim/dyn, end = 0.5, &\n dtout = 0.25\nstop\n")
    m = _load(path)
    assert [(c.end_time, c.print_interval) for c in m.commands] == [(0.5, 0.25)]
    assert (m.graphics[2].type, m.graphics[2].attrs) == \
        ("BOX", {"corner": "3", "x": "0.2", "y": ".2", "z": "4"})      # kept as written
    res = m.run()
    np.testing.assert_allclose(res.request(1)[:, 7], 2 * res.t, atol=1e-12)   # wz = T t / I
    np.testing.assert_allclose(res.request(2)[:, 7], 2.0, atol=1e-12)
    (tmp_path / "s.acf").write_text("s\n\nDEACTIVATE/SENSOR, ID = 1\nstop\n")
    with pytest.raises(DeckError, match="the command DEACTIVATE is not supported") as err:
        _load(path)
    assert err.value.file.endswith("s.acf") and err.value.line == 3


def test_a_command_file_that_names_its_dataset_with_file_model(tmp_path):
    """A blank first line, then FILE/MODEL=name (the layout adamspy writes)."""
    shutil.copy(ADAMS / "every_statement.adm", tmp_path / "m.adm")
    (tmp_path / "run.acf").write_text("\nfile/model=m\n! commands:\n"
                                      "SIMULATE/DYNAMIC, END=0.4, DTOUT=0.1\nstop\n")
    m = _load(tmp_path / "run.acf")
    assert [(c.end_time, c.print_interval) for c in m.commands] == [(0.4, 0.1)]


#: A dataset whose lines 2 to 5 hold no statement, with an INTEGRATOR (line 10) and a
#: velocity motion (line 11).
_LOCATED = """a dataset whose lines 2 to 5 hold no statement
! line 2
! line 3
! line 4
! line 5
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 2, IP = 1, 1, 1
MARKER/2, PART = 2
INTEGRATOR/ERROR = 1E-6
MOTION/1, I = 2, J = 1, X, VELOCITY, FUNCTION = 0
END
"""


@pytest.mark.parametrize("commands, line, element, attribute, reason", [
    (["SIMULATE/DYNAMICS, END = 3.0, DTOUT = 0"], 3, "SIMULATE (Simulate)", "DTOUT",
     "got 0; expected a value > 0"),
    (["SIMULATE/DYNAMICS, END = -3.0, DTOUT = 0.01"], 3, "SIMULATE (Simulate)", "END",
     "END -3 must be after the start time 0"),
    (["SIMULATE/DYNAMICS, END = 1, DTOUT = 0.1", "! a comment", "SIMULATE/DYNAMICS, END = 0.5"],
     5, "SIMULATE (Simulate)", "END", "END 0.5 must be after the start time 1"),
    (["SIMULATE/DYNAMICS, END = 1, STEPS = 0"], 3, "SIMULATE (Simulate)", "STEPS",
     "got 0; expected a positive integer"),
    (["SIMULATE/DYNAMICS, START = 2, END = 3"], 3, "SIMULATE (Simulate)", "START",
     "got 2; a run starts at TIME = 0 (pysolver has no other start time): leave START out "
     "or give 0"),
    (["SIMULATE/INITIAL_CONDITIONS, END = 3"], 3, "SIMULATE (Simulate)", "END",
     "an Assembly analysis takes no end time or output interval"),
    (["INTEGRATOR/ERROR = -1"], 3, "INTEGRATOR (Param_Transient)", "ERROR",
     "got -1; expected a value > 0"),
    (["INTEGRATOR/HMAX = 0.01", "INTEGRATOR/HMIN = 0"], 4, "INTEGRATOR (Param_Transient)",
     None, "a second Param_Transient (the first is on line 3; in a Python deck INTEGRATOR, "
     "EQUILIBRIUM or ACCGRAV); give one"),
    (["SIMULATE/DYNAMICS, END = 1, DTOUT = 0.1", "INTEGRATOR/HMAX = 0.01"], 4, "INTEGRATOR",
     None, "INTEGRATOR after a SIMULATE it applies to would change the settings between "
     "analyses, and pysolver runs every analysis with one set of settings: give it before "
     "that SIMULATE"),
    (["EQUILIBRIUM/MAXIT = -1", "SIMULATE/STATICS"], 3, "EQUILIBRIUM (Param_Static)", "MAXIT",
     "got -1; expected a positive integer"),
    (["EQUILIBRIUM/METHOD = MKEAM", "SIMULATE/STATICS, END = 1, STEPS = 10"], 4, "Simulate",
     "analysis_type",
     "MKEAM does not do quasi-static analyses (seed 004); use FIM_D or FIM_S in Param_Static"),
    (["SIMULATE/STATICS"], 3, "Simulate", "analysis_type",
     "static analyses hold each motion's displacement, and Motion_Marker 1 gives a velocity "
     "(val_type V); write it as a displacement (val_type D), or run the scene as a transient"),
])
def test_every_error_a_command_causes_names_the_command_file_and_its_line(
        tmp_path, commands, line, element, attribute, reason):
    """The checks of the element a command becomes (a Simulate's times, Param_Transient's
    and Param_Static's values, a second Param_Transient, the checks across commands) name
    the .acf and the command's line, never the dataset's line of the same number; loading
    the .adm (the .acf beside it) says the same."""
    adm, acf = tmp_path / "d.adm", tmp_path / "d.acf"
    adm.write_text(_LOCATED)
    acf.write_text("d\nd\n" + "\n".join(commands) + "\nSTOP\n")
    reason = reason.format(adm=adm)
    where = f"{acf}:{line}, {element}" + (f", attribute '{attribute}'" if attribute else "")
    for path in (acf, adm):
        with pytest.raises(DeckError) as err:
            _load(path)
        assert (err.value.file, err.value.line, err.value.reason) == (str(acf), line, reason)
        assert str(err.value) == f"{where}: {reason}"


def test_an_integrator_command_changes_the_datasets_integrator(tmp_path):
    """Adams lets a command change the dataset's settings (a second Param_Transient was
    refused): the keywords the command gives replace the dataset's, the others are kept, and
    an error in a kept one names the dataset's line; an INTEGRATOR after a SIMULATE/STATICS
    (which it does not apply to) is taken."""
    adm, acf = tmp_path / "d.adm", tmp_path / "d.acf"
    adm.write_text(_LOCATED.replace("MOTION/1, I = 2, J = 1, X, VELOCITY, FUNCTION = 0\n", ""))
    acf.write_text("d\nd\nINTEGRATOR/HMAX = 0.01\nSIMULATE/DYNAMICS, END = 0.1, DTOUT = 0.05\n"
                   "STOP\n")
    settings = _load(acf).transient
    assert (settings.integr_tol, settings.h_max) == (1e-6, 0.01)
    acf.write_text("d\nd\nSIMULATE/STATICS\nINTEGRATOR/ERROR = 1e-8\n"
                   "SIMULATE/DYNAMICS, END = 0.1, DTOUT = 0.05\nSTOP\n")
    assert _load(acf).transient.integr_tol == 1e-8
    adm.write_text(adm.read_text().replace("INTEGRATOR/ERROR = 1E-6", "INTEGRATOR/ERROR = -1"))
    acf.write_text("d\nd\nINTEGRATOR/HMAX = 0.01\nSTOP\n")
    with pytest.raises(DeckError) as err:
        _load(acf)
    assert (err.value.file, err.value.line, err.value.attribute) == (str(adm), 10, "ERROR")


def test_pysolver_run_names_the_command_file_line_of_a_bad_dtout(tmp_path, capsys):
    """The new user's case: `pysolver run a_dt.acf` with DTOUT = 0 on the .acf's line 3 (the
    .adm's line 3 a comment): one line naming a_dt.acf:3, exit 2; a warning a command draws
    names it too."""
    shutil.copy(DECKS / "forms" / "adams" / "catenary_bead.adm", tmp_path / "a_dt.adm")
    acf = tmp_path / "a_dt.acf"
    acf.write_text("a_dt\na_dt\nSIMULATE/DYNAMICS, END = 3.0, DTOUT = 0\nSTOP\n")
    assert main(["run", str(acf), "-q", "--no-plot", "-o", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err == (f"pysolver: error: {acf}:3, SIMULATE (Simulate), "
                                       "attribute 'DTOUT': got 0; expected a value > 0\n")
    acf.write_text("a_dt\na_dt\nINTEGRATOR/HHT\nSTOP\n")
    (tmp_path / "a_dt.adm").write_text(
        (DECKS / "forms" / "adams" / "catenary_bead.adm").read_text().replace(
            "INTEGRATOR/ERROR = 1e-06\n", ""))
    with pytest.warns(DeckWarning, match="HHT is not pysolver's integrator") as got:
        pysolver.load(acf)
    assert [(w.message.file, w.message.line) for w in got] == [(str(acf), 3)]


@pytest.mark.parametrize("where", ["adm", "acf"])
def test_lsolver_is_set_aside_with_a_warning(tmp_path, where):
    """LSOLVER/CALAHAN only chooses Adams' linear solver: a DeckWarning naming its line, in
    the dataset or the command file, and the model loads as without it."""
    adm = (DECKS / "forms" / "adams" / "catenary_bead.adm").read_text()
    acf = "bead\nbead\nSIMULATE/DYNAMICS, END = 0.1, DTOUT = 0.01\nSTOP\n"
    if where == "adm":
        adm = adm.replace("END\n", "LSOLVER/CALAHAN\nEND\n")
    else:
        acf = acf.replace("SIMULATE", "LSOLVER/CALAHAN\nSIMULATE")
    (tmp_path / "bead.adm").write_text(adm)
    (tmp_path / "bead.acf").write_text(acf)
    line = (adm if where == "adm" else acf).splitlines().index("LSOLVER/CALAHAN") + 1
    with pytest.warns(DeckWarning) as got:
        model = pysolver.load(tmp_path / "bead.acf")
    lsolver = [w.message for w in got if "LSOLVER" in str(w.message)]
    assert [(m.file, m.line) for m in lsolver] == [(str(tmp_path / f"bead.{where}"), line)]
    assert str(lsolver[0]).endswith("LSOLVER only chooses Adams' linear solver (pysolver "
                                    "chooses its own, dense or sparse LU); set aside")
    assert model.commands[0].end_time == 0.1
