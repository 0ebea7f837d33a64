"""Every kind of bad input gives one DeckError naming file, line, element, id and attribute."""
import pytest

import pysolver
from pysolver import DeckError

from helpers import DECKS

HEAD = '<MotionSolve>\n<Model>\n<Body_Rigid id="1" isground="TRUE"/>\n'
BASE = ('<Reference_Marker id="10" body_id="2" pos_z="1"/>\n'
        '<Body_Point id="2" cg_id="10" mass="1"/>\n')
TAIL = '</Model>\n<Simulate analysis_type="Transient" end_time="1" print_interval="0.1"/>\n</MotionSolve>\n'


def deck(body, base=BASE):
    return HEAD + base + body + TAIL


def check(text, line, element, attribute=None, id=None, match=None, fmt="xml"):
    with pytest.raises(DeckError) as info:
        pysolver.loads(text, fmt=fmt, file="scene." + fmt)
    err = info.value
    assert err.file == "scene." + fmt
    assert err.line == line, str(err)
    assert err.element == element, str(err)
    assert err.attribute == attribute, str(err)
    if id is not None:
        assert err.id == id, str(err)
    msg = str(err)
    assert f"scene.{fmt}:{line}" in msg
    if attribute:
        assert f"attribute '{attribute}'" in msg
    if match:
        assert match in msg, msg
    return err


PEN = '<Force_Penalty id="7" expr="DZ(10)-1" penalty="10"{extra}/>\n'


@pytest.mark.parametrize("body,attr,match", [
    (PEN.format(extra=' penalty1="-1"'), "penalty1", "expected a value >= 0"),
    ('<Force_Penalty id="7" expr="DZ(10)-1" penalty="-5"/>\n', "penalty", "expected a value > 0"),
    (PEN.format(extra=' unilateral="TRUE" smoothing_factor="0"'), "smoothing_factor", "> 0"),
    (PEN.format(extra=' unilateral="maybe"'), "unilateral", "expected TRUE or FALSE"),
    (PEN.format(extra=' color="red"'), "color", "unknown attribute"),
    ('<Force_Penalty id="7" expr="DZ(10)-1"/>\n', "penalty", "missing required attribute"),
    ('<Force_Penalty id="7" expr="DZ(10)-1" penalty="ten"/>\n', "penalty", "expected a real number"),
    ('<Force_Penalty id="7" expr="DZ(10) - " penalty="1"/>\n', "expr", "bad expression"),
    ('<Force_Penalty id="7" expr="FOO(10)" penalty="1"/>\n', "expr", "unknown function FOO"),
    ('<Force_Penalty id="7" expr="STEP(DZ(10),0,1)" penalty="1"/>\n', "expr",
     "STEP takes 5 arguments, got 3"),
    ('<Force_Penalty id="7" expr="DZ(99)" penalty="1"/>\n', "expr", "marker id 99"),
    ('<Force_Penalty id="7" expr="VZ(10)" penalty="1"/>\n', "expr", "displacement measures only"),
    ('<Force_Penalty id="7" expr="VARVAL(3)" penalty="1"/>\n', "expr", "variable id 3"),
    ('<Force_Penalty id="7" type="USERSUB" script_name="a.m" interpreter="MATLAB" penalty="1"/>\n',
     "interpreter", "MATLAB user subroutines are not supported"),
])
def test_force_penalty_attributes(body, attr, match):
    check(deck(body), 6, "Force_Penalty", attr, id=7, match=match)


def test_malformed_xml():
    err = check(HEAD + BASE + "<Force_Penalty id='1'\n" + TAIL, 7, None, match="malformed XML")
    assert "malformed" in str(err)


def test_unknown_element():
    check(deck('<Force_Magic id="1"/>\n'), 6, "Force_Magic", match="unknown element")


def test_duplicate_id():
    check(deck(PEN.format(extra="") + PEN.format(extra="")), 7, "Force_Penalty", "id", id=7,
          match="duplicate penalty id 7 (first defined on line 6)")


def test_marker_on_missing_body():
    check(deck("", base='<Reference_Marker id="10" body_id="5"/>\n'), 4, "Reference_Marker",
          "body_id", id=10, match="body 5 does not exist")


def test_a_cg_marker_on_a_missing_body_names_the_missing_body():
    """It blamed the body's cg_id ("marker 10 belongs to body 7, not to this body")."""
    check(deck("", base='<Reference_Marker id="10" body_id="7"/>\n'
                        '<Body_Point id="2" cg_id="10" mass="1"/>\n'), 4, "Reference_Marker",
          "body_id", id=10, match="body 7 does not exist")


def test_body_with_missing_marker():
    check(deck("", base='<Body_Point id="2" cg_id="11" mass="1"/>\n'), 4, "Body_Point", "cg_id",
          id=2, match="marker 11 does not exist")


def test_wrong_type_of_id():
    check(deck('<Post_Request id="x1" expr1="DZ(10)"/>\n'), 6, "Post_Request", "id",
          match="expected a positive integer")


def test_variable_cycle():
    text = deck('<Reference_Variable id="1" expr="VARVAL(2)"/>\n'
                '<Reference_Variable id="2" expr="VARVAL(1)+1"/>\n')
    check(text, 6, "Reference_Variable", "expr", id=1, match="VARVAL cycle")


def test_incomplete_orientation():
    check(deck("", base='<Reference_Marker id="10" body_id="1" e0="1" e1="0"/>\n'), 4,
          "Reference_Marker", "e2", id=10, match="incomplete")


def test_simulate_without_end_time():
    text = HEAD + BASE + '</Model>\n<Simulate analysis_type="Transient" print_interval="0.1"/>\n</MotionSolve>'
    check(text, 7, "Simulate", "end_time", match="exactly one of end_time and duration")


def test_usersub_in_python_deck_and_python_line_numbers():
    text = ("PART(1, GROUND=True)\nMARKER(10, PART=2, QP=[0, 0, 1])\nPOINT_MASS(2, MASS=1, CM=10)\n"
            "PFORCE(3, FUNCTION='DZ(10)-1', PENALTY=-1)\n")
    check(text, 4, "Force_Penalty", "PENALTY", id=3, match="expected a value > 0", fmt="py")


def test_python_deck_unknown_argument():
    check("PART(1, GROUND=True)\nPFORCE(3, FUNCTON='DZ(10)', PENALTY=1)\n", 2, "PFORCE",
          "FUNCTON", id=3, match="unknown argument", fmt="py")


def test_python_deck_runtime_error_names_line():
    check("PART(1, GROUND=True)\nx = 1/0\n", 2, None, match="ZeroDivisionError", fmt="py")


def test_xml_deck_never_executes_code(tmp_path):
    """External entities are not resolved and no file is read."""
    secret = tmp_path / "secret.txt"
    secret.write_text("TOPSECRET")
    text = (f'<?xml version="1.0"?>\n<!DOCTYPE m [<!ENTITY x SYSTEM "file://{secret}">]>\n'
            '<MotionSolve><Model><Body_Rigid id="1" isground="TRUE" label="&x;"/></Model></MotionSolve>')
    try:
        model = pysolver.loads(text)
    except DeckError:
        return
    assert "TOPSECRET" not in repr(model.bodies[1].label)


def test_nothing_runs_half_way():
    """A deck with an error in its last element builds nothing: load raises before any run."""
    text = deck(PEN.format(extra="") + '<Post_Request id="1" expr1="DZ(10"/>\n')
    with pytest.raises(DeckError, match="Post_Request id=1"):
        pysolver.loads(text)


@pytest.mark.parametrize("old,new,element,chain", [
    ('expr="2*TIME"', 'expr="2*TIME + SFORCE(1,0,1,0)"', "Force_Scalar_TwoBody",
     "SFORCE(1) -> SFORCE(1)"),
])
def test_force_reference_cycles_are_deck_errors(old, new, element, chain):
    """Found by the fuzzer: a force whose expression reads its own SFORCE/PFORCE recursed
    until RecursionError."""
    text = (DECKS / "sensor_halt_acceleration.xml").read_text().replace(old, new)
    with pytest.raises(pysolver.DeckError, match="refer to each other in a cycle") as info:
        pysolver.loads(text)
    assert info.value.element == element and chain in str(info.value)


def test_a_penalty_reading_its_own_pforce_is_a_cycle():
    text = (DECKS / "particle_above_line.xml").read_text().replace(
        'expr="1 + dx(10) - dy(10)"', 'expr="1 + dx(10) - dy(10) + PFORCE(10)"')
    with pytest.raises(pysolver.DeckError, match=r"cycle: PFORCE\(10\) -> PFORCE\(10\)"):
        pysolver.loads(text)


@pytest.mark.parametrize("text,fmt", [
    ("", "py"),
    ('<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/></Model>'
     '<Simulate analysis_type="Transient" end_time="1" print_interval="0.1"/></MotionSolve>',
     "xml")])
def test_a_deck_without_a_moving_body_is_a_deck_error_when_run(text, fmt):
    """Found by the fuzzer (an empty Python deck): the run crashed in NumPy. Loading such a deck
    (to read its markers) is fine; running or checking it is a DeckError."""
    model = pysolver.loads(text, fmt=fmt)
    for call in (model.run, model.check):
        with pytest.raises(pysolver.DeckError, match="no moving body"):
            call()


@pytest.mark.parametrize("name", ["nodeck.xml", "nodeck.py", "nodeck.adm", "nodeck.acf",
                                  "nodeck"])
def test_a_deck_that_does_not_exist_is_a_deck_error(tmp_path, name):
    """It was a bare FileNotFoundError, which ``except pysolver.DeckError`` missed; it is
    both, naming the file."""
    path = tmp_path / name
    for catch in (DeckError, FileNotFoundError):
        with pytest.raises(catch) as info:
            pysolver.load(path)
        assert str(info.value) == f"{path}: no such file"
        assert info.value.file == info.value.filename == str(path)


def test_an_acf_naming_a_dataset_that_does_not_exist(tmp_path):
    (tmp_path / "run.acf").write_text("gone\nrun\nSIMULATE/DYNAMICS, END = 1, DTOUT = 0.1\n"
                                      "STOP\n")
    with pytest.raises(FileNotFoundError) as info:
        pysolver.load(tmp_path / "run.acf")
    assert isinstance(info.value, DeckError) and info.value.line == 1
    assert info.value.filename == str(tmp_path / "gone.adm")      # what is missing
    assert str(info.value) == (f"{tmp_path / 'run.acf'}:1: the dataset {tmp_path / 'gone.adm'} "
                               "named on the first line does not exist")


def test_deck_errors_keep_their_fields_through_pickling(tmp_path):
    """A sweep's worker sends its errors to the parent pickled: every field survives (a
    MissingFileError's text doubled, and its filename became the message)."""
    import pickle
    err = DeckError("got -1; expected a value > 0", file="d.xml", line=7,
                    element="Force_Penalty", id=3, attribute="penalty")
    back = pickle.loads(pickle.dumps(err))
    assert (type(back), str(back), back.reason, back.file, back.line, back.element, back.id,
            back.attribute) == (DeckError, str(err), err.reason, "d.xml", 7, "Force_Penalty",
                                3, "penalty")
    with pytest.raises(FileNotFoundError) as info:
        pysolver.load(tmp_path / "none.xml")
    back = pickle.loads(pickle.dumps(info.value))
    assert (type(back), str(back), back.filename, back.errno) == (
        type(info.value), f"{tmp_path / 'none.xml'}: no such file", str(tmp_path / "none.xml"), 2)
