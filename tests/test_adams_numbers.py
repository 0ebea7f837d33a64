"""Numbers of an Adams dataset and command file (docs/adams.md, "Numbers"): a D after a number
is degrees, a D followed by an exponent (1.0D-3, 1.0D+3, 1.0D3) the Fortran double precision
exponent, read the same way in functions, argument lists and command files; a signed D
exponent in a function, which also reads as degrees plus or minus a number, draws a
DeckWarning naming the line."""
import math
import warnings

import numpy as np
import pytest
from lxml import etree

import pysolver
from pysolver import DeckError, DeckWarning
from pysolver.convert import convert
from pysolver.deck.adams import read_elements
from pysolver.rotations import rot_313

_DATASET = """numbers in D notation
UNITS/SYSTEM=MKS
PART/1, GROUND
MARKER/1, PART=1
MARKER/2, PART=1, QP=1.0D+02, 2.5D-1, 5D2, REULER=0.5D, 1.0D-1, 0
PART/2, MASS=2.0D0, CM=20, IP=1.0D-1, 1.0D-1, 1.0D-1
MARKER/20, PART=2
ACCGRAV/JGRAV=-9.81
REQUEST/1, F1=1.0D+3\\F2=1.0D3\\F3=2.5D-1*TIME\\F4=2.5D - 1\\F5=(2.5D)-1\\F6=5D2
, \\F7=30D+10D*TIME\\F8=1.5E-1D\\
END
"""
_COMMANDS = """numbers
numbers_out
INTEGRATOR/ERROR=1.0D-6
SIMULATE/DYNAMICS, END=1.0D0, DTOUT=2.5D-1
STOP
"""


def _read(tmp_path, dataset=_DATASET, commands=_COMMANDS):
    (tmp_path / "numbers.adm").write_text(dataset)
    (tmp_path / "numbers.acf").write_text(commands)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = pysolver.load(tmp_path / "numbers.acf")
    return model, [w.message for w in caught if issubclass(w.category, DeckWarning)]


def test_each_form_in_a_function_has_its_value(tmp_path):
    """1.0D+3 = 1.0D3 = 1000, 2.5D-1 = 0.25, 5D2 = 500; 2.5D - 1 and (2.5D)-1 are 2.5
    degrees minus 1, 30D+10D two angles (the digits after the sign run into a D), 1.5E-1D
    0.15 degrees."""
    model, _ = _read(tmp_path)
    res = model.run()
    assert res.success, res.message
    t = res.t
    expected = [np.full_like(t, 1000.0), np.full_like(t, 1000.0), 0.25 * t,
                np.full_like(t, math.radians(2.5) - 1), np.full_like(t, math.radians(2.5) - 1),
                np.full_like(t, 500.0), math.radians(30) + math.radians(10) * t,
                np.full_like(t, math.radians(0.15))]
    np.testing.assert_allclose(res.request(1), np.column_stack(expected), rtol=1e-15,
                               atol=1e-15)
    assert list(t) == [0.0, 0.25, 0.5, 0.75, 1.0]


def test_each_form_in_an_argument_list_and_a_command_file_has_its_value(tmp_path):
    """QP = 1.0D+02, 2.5D-1, 5D2 (refused before: "QP takes three numbers"), REULER = 0.5D,
    1.0D-1, 0 (refused before: "unknown keyword 1.0D-1"), MASS and IP; the command file's
    END, DTOUT and INTEGRATOR's ERROR."""
    model, _ = _read(tmp_path)
    assert model.markers[2].pos.tolist() == [100.0, 0.25, 500.0]
    np.testing.assert_array_equal(model.markers[2].rot, rot_313(math.radians(0.5), 0.1, 0.0))
    assert model.bodies[2].mass == 2.0
    assert np.diag(model.bodies[2].inertia).tolist() == [0.1, 0.1, 0.1]
    assert [(c.analysis, c.end_time, c.print_interval) for c in model.commands] == \
        [("TRANSIENT", 1.0, 0.25)]
    assert model.transient.integr_tol == 1e-6


def test_a_signed_d_exponent_in_a_function_draws_a_warning_naming_its_line(tmp_path):
    """Only there is the text read two ways (1.0D+3 or 1.0D + 3); the unsigned form, the
    argument lists and the command file draw none."""
    _, caught = _read(tmp_path)
    assert [(w.line, w.element, w.attribute, w.reason) for w in caught] == [
        (9, "REQUEST/1", "F1", "1.0D+3 is read as a Fortran exponent, 1000.0, not as 1.0 "
         "degrees plus 3; write 1.0E+3 for the number, or 1.0D + 3 for the angle "
         "(docs/adams.md, \"Numbers\")"),
        (9, "REQUEST/1", "F3", "2.5D-1 is read as a Fortran exponent, 0.25, not as 2.5 degrees "
         "minus 1; write 2.5E-1 for the number, or 2.5D - 1 for the angle (docs/adams.md, "
         "\"Numbers\")")]
    assert all(w.file == str(tmp_path / "numbers.adm") for w in caught)


def test_user_parameters_take_d_exponents_without_a_warning():
    """USER(...) holds numbers only, so 1.0D-3 there has one reading."""
    text = "x\nVARIABLE/1, FUNCTION=USER(1.0D-3, 2.5D+1, 90D)\\, ROUTINE=lib::f\nEND\n"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        elements = read_elements(text, "user.adm")
    assert elements[0][1]["expr"] == "USER(1.0E-3, 2.5E+1, 1.5707963267948966)"


def test_converted_functions_hold_e_exponents_and_radians(tmp_path):
    """The XML shows how each function was read (the D exponents as E, degrees in radians);
    the XML converted back to a dataset reads to the same numbers."""
    _read(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeckWarning)
        convert(tmp_path / "numbers.acf", tmp_path / "numbers.xml")
        convert(tmp_path / "numbers.xml", tmp_path / "again.adm")
        again = pysolver.load(tmp_path / "again.adm")
    request = etree.parse(str(tmp_path / "numbers.xml")).find(".//Post_Request")
    assert [request.get(f"expr{k}") for k in range(1, 9)] == [
        "1.0E+3", "1.0E3", "2.5E-1*TIME", "0.04363323129985824 - 1",
        "(0.04363323129985824)-1", "5E2", "0.5235987755982988+0.17453292519943295*TIME",
        "0.002617993877991494"]
    res = again.run()
    assert res.success and res.request(1)[-1, :3].tolist() == [1000.0, 1000.0, 0.25]


@pytest.mark.parametrize("statement, element, attribute, reason", [
    # the digits of an exponent run into a D: no number (two angles, 1.0D + 3D, in a function)
    ("MARKER/3, PART=1, REULER=0.5D, 1.0D+3D, 0", "MARKER/3", "REULER",
     "REULER takes three numbers, got [0.008726646259971648, '1.0D+3D', 0]"),
    ("PART/3, MASS=1.0D+3D, CM=20", "PART/3 (Body_Rigid)", "MASS",
     "got '1.0D+3D'; expected a real number"),
    ("REQUEST/2, F1=1.0D3D*TIME\\", "REQUEST/2 (Post_Request)", "F1",
     "bad expression '1.0D3D*TIME': unexpected 'D3D' after the end of the expression (at "
     "column 4)"),
])
def test_a_malformed_number_is_a_deck_error_naming_its_line(tmp_path, statement, element,
                                                            attribute, reason):
    dataset = _DATASET.replace("END\n", f"{statement}\nEND\n")
    with pytest.raises(DeckError) as err:
        _read(tmp_path, dataset)
    assert (err.value.line, err.value.element, err.value.attribute, err.value.reason) == \
        (11, element, attribute, reason)
