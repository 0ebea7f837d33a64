"""Adams datasets converted by pysolver convert and read again: markers of parts placed by
QG/REULER written with Adams' REULER (3-1-3 angles, gimbal lock included), the command file's
output name and analyses, Simulate messages in the command's keywords, and the output row of
a static analysis between two transients (docs/adams.md, "Writing datasets", "Commands";
docs/usage.md, "Output rows")."""
import math
import warnings

import numpy as np
import pytest

import pysolver
from pysolver import DeckError, DeckWarning
from pysolver.cli import main
from pysolver.convert import convert
from pysolver.rotations import angles_313, rot_313

#: Parts placed by QG and REULER (one turned to theta = 0), markers on them by QP/REULER (one
#: with its z axis down), ZP/XP and RM.
_DATASET = """moved parts
UNITS/SYSTEM=MKS
PART/1, GROUND
MARKER/1, PART=1
MARKER/12, PART=1, REULER=90D,90D,0D
PART/2, MASS=1, CM=20, IP=1,1,1, QG=0.5,0,0, REULER=30D,40D,50D
MARKER/20, PART=2, QP=0,0,0, REULER=-50D,-40D,-30D
MARKER/21, PART=2, QP=1,2,3, REULER=90D,90D,0D
MARKER/22, PART=2, QP=0,1,0, ZP=0,1,1, XP=1,1,0
MARKER/23, PART=2, RM=21, REULER=0,180D,0
PART/3, MASS=1, CM=30, IP=1,1,1, QG=0,0,1, REULER=20D,0D,0D
MARKER/30, PART=3
MARKER/31, PART=3, REULER=0D,180D,0D
ACCGRAV/IGRAV=-9.81
END
"""
#: A slider on a spring along x under gravity along -x: at rest at x = 0.4 - 9.81/100.
_SPRING = """spring and mass
UNITS/SYSTEM=MKS
PART/1, GROUND
MARKER/1, PART=1
MARKER/12, PART=1, REULER=90D,90D,0D
PART/2, MASS=1, CM=20, IP=1,1,1, QG=0.5,0,0
MARKER/20, PART=2
MARKER/21, PART=2, REULER=90D,90D,0D
JOINT/1, TRANSLATIONAL, I=21, J=12
SPRINGDAMPER/1, TRANSLATIONAL, I=20, J=1, K=100, C=1, LENGTH=0.4
ACCGRAV/IGRAV=-9.81
REQUEST/1, F1=DX(20)\\F2=VX(20)\\
END
"""
_COMMANDS = """moved
moved_run
simulate/kinematic, end=1.0, steps=4
SIMULATE/STATICS
SIMULATE/DYNAMICS, END=2.0, DTOUT=0.5
STOP
"""


def _deck(tmp_path, commands=_COMMANDS, dataset=_DATASET):
    (tmp_path / "moved.adm").write_text(dataset)
    (tmp_path / "moved.acf").write_text(commands)
    return tmp_path / "moved.acf"


def _load(path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeckWarning)
        return pysolver.load(path, **kw)


def test_markers_of_moved_parts_are_written_with_reuler_and_read_back_to_rounding(tmp_path):
    """No pysolver AXES: each marker of parts 2 and 3 (placed in ground by the reader) is
    written with ZP/XP where those give its axes exactly, else REULER in radians; read
    again, the markers sit where they sat (bit for bit) with the axes they had to 2e-15, and
    a second conversion writes the same dataset."""
    source = _load(_deck(tmp_path))
    out = tmp_path / "out"
    out.mkdir()
    convert(_deck(tmp_path), out / "moved.adm")
    text = (out / "moved.adm").read_text()
    assert "AXES" not in text
    lines = text.splitlines()
    # part 3 turned 20 degrees about z: marker 30 (at theta = 0) by the points its axes give
    # exactly, marker 31 (at theta = pi) by its angles
    assert lines[lines.index("MARKER/30, PART = 3, QP = 0.0, 0.0, 1.0, ZP = 0.0, 0.0, 2.0") + 1] \
        == ", XP = 0.9396926207859084, 0.3420201433256687, 1.0"
    assert lines[lines.index("MARKER/31, PART = 3, QP = 0.0, 0.0, 1.0") + 1] == \
        ", REULER = 0.34906585039886595, 3.141592653589793, 0.0"
    again = _load(out / "moved.adm")
    assert sorted(again.markers) == sorted(source.markers)
    for mid, m in source.markers.items():
        assert again.markers[mid].pos.tolist() == m.pos.tolist(), mid
        assert np.abs(again.markers[mid].rot - m.rot).max() <= 2e-15, mid
    convert(out / "moved.acf", tmp_path / "twice.adm")
    assert (tmp_path / "twice.adm").read_text().splitlines()[1:] == text.splitlines()[1:]


@pytest.mark.parametrize("theta", [0.0, 1e-300, 1e-12, 1e-6, 0.3, math.pi / 2, 2.9,
                                   math.pi - 1e-6, math.pi - 1e-12, math.pi])
def test_the_313_angles_give_the_rotation_back_to_rounding(theta):
    """rot_313(angles_313(A)) is A to 2e-15 at every theta, near and at gimbal lock (where
    psi and phi turn about one axis: then their sum, or difference, is what counts);
    theta in [0, pi], psi and phi in [-pi, pi]."""
    rng = np.random.default_rng(7)
    for psi, phi in rng.uniform(-math.pi, math.pi, (200, 2)):
        A = rot_313(psi, theta, phi)
        a = angles_313(A)
        assert np.abs(rot_313(*a) - A).max() <= 2e-15, (psi, theta, phi, a)
        assert 0.0 <= a[1] <= math.pi and abs(a[0]) <= math.pi and abs(a[2]) <= math.pi


def test_at_gimbal_lock_phi_is_zero():
    """A rotation about z alone (theta = 0 exactly) is psi; one that turns z down (theta = pi
    exactly) psi with phi 0; a turn about y (the flyball's 30 degrees) takes psi = 90 degrees,
    phi = -90 degrees."""
    c, s = math.cos(0.3), math.sin(0.3)
    assert angles_313(np.eye(3)) == (0.0, 0.0, 0.0)
    assert angles_313([[c, -s, 0], [s, c, 0], [0, 0, 1]]) == (0.3, 0.0, 0.0)
    assert angles_313(np.diag([1.0, -1.0, -1.0])) == (0.0, math.pi, 0.0)
    assert angles_313([[c, s, 0], [s, -c, 0], [0, 0, -1]]) == (0.3, math.pi, 0.0)
    c, s = math.cos(math.pi / 6), math.sin(math.pi / 6)
    assert angles_313([[c, 0, s], [0, 1, 0], [-s, 0, c]]) == \
        (math.pi / 2, math.pi / 6, -math.pi / 2)


def test_the_command_file_keeps_its_output_name_and_its_analyses(tmp_path):
    """The second line (moved_run) is kept, in the .acf and in the script of msolve classes;
    SIMULATE/KINEMATICS is written as SIMULATE/DYNAMICS (the model keeps no kinematic
    analysis: pysolver runs both as a transient)."""
    convert(_deck(tmp_path), tmp_path / "new.adm")
    assert (tmp_path / "new.acf").read_text().splitlines() == [
        "new", "moved_run", "SIMULATE/DYNAMICS, END = 1.0, STEPS = 4", "SIMULATE/STATICS",
        "SIMULATE/DYNAMICS, END = 2.0, DTOUT = 0.5", "STOP"]
    convert(tmp_path / "new.acf", tmp_path / "script.py")
    assert "model = Model(output='moved_run')" in (tmp_path / "script.py").read_text()
    # the dataset converted alone takes the command file beside it, output name and all
    convert(tmp_path / "moved.adm", tmp_path / "alone.adm")
    assert (tmp_path / "alone.acf").read_text().splitlines()[:2] == ["alone", "moved_run"]
    assert [c.analysis for c in _load(tmp_path / "new.acf").commands] == \
        ["TRANSIENT", "STATIC", "TRANSIENT"]


def test_a_command_file_naming_its_dataset_with_file_model_has_no_output_name(tmp_path):
    """Its second line is FILE/MODEL=: the converted command file takes the new stem."""
    acf = _deck(tmp_path, "\nFILE/MODEL=moved\nSIMULATE/DYNAMICS, END=1, DTOUT=0.5\nSTOP\n")
    convert(acf, tmp_path / "new.adm")
    assert (tmp_path / "new.acf").read_text().splitlines()[:2] == ["new", "new"]


def test_a_simulate_with_dtout_and_steps_names_the_commands_keywords(tmp_path, capsys):
    """In a command file the message names DTOUT and STEPS, in XML print_interval and
    num_step; pysolver run prints it as its one error line."""
    acf = _deck(tmp_path, "moved\nmoved_run\nSIMULATE/DYNAMIC, END=1, STEPS=10, DTOUT=0.1\n"
                          "STOP\n")
    with pytest.raises(DeckError) as err:
        _load(acf)
    assert str(err.value) == (f"{acf}:3, SIMULATE (Simulate), attribute 'STEPS': give one of "
                              "DTOUT and STEPS")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeckWarning)
        assert main(["run", str(acf), "-o", str(tmp_path / "o"), "-q", "--no-plot",
                     "--no-animation"]) == 2
    assert capsys.readouterr().err.splitlines() == [f"pysolver: error: {err.value}"]
    xml = ('<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/></Model>'
           '<Simulate analysis_type="Transient" end_time="1" num_step="10" '
           'print_interval="0.1"/></MotionSolve>')
    with pytest.raises(DeckError) as err:
        pysolver.loads(xml)
    assert (err.value.attribute, err.value.reason) == \
        ("num_step", "give one of print_interval and num_step")


@pytest.mark.parametrize("commands, reason", [
    ("SIMULATE/DYNAMICS, END=1, DTOUT=0.5\nSIMULATE/DYNAMICS, END=0.5",
     "END 0.5 must be after the start time 1"),
    ("SIMULATE/DYNAMICS, END=1, DURATION=1", "give exactly one of END and DURATION"),
    ("SIMULATE/DYNAMICS, END=1, DTOUT=0.5\nSIMULATE/STATICS, END=0.5",
     "END 0.5 is before the current time 1"),
])
def test_other_simulate_messages_name_the_commands_keywords(tmp_path, commands, reason):
    acf = _deck(tmp_path, f"moved\nmoved_run\n{commands}\nSTOP\n")
    with pytest.raises(DeckError) as err:
        _load(acf)
    assert err.value.reason == reason


def test_a_static_between_two_transients_gives_the_one_row_at_its_time(tmp_path):
    """Transient to 0.5, statics, transient to 1: one row per time, the row at 0.5 holds the
    equilibrium (x = 0.4 - 9.81/100, at rest), not the transient's state there (the
    transient alone: x = 0.3377, moving); res.statics records it."""
    acf = _deck(tmp_path, "moved\nmoved_run\nSIMULATE/DYNAMICS, END=0.5, DTOUT=0.25\n"
                          "SIMULATE/STATICS\nSIMULATE/DYNAMICS, END=1, DTOUT=0.25\nSTOP\n",
                _SPRING)
    res = _load(acf).run()
    assert res.success, res.message
    assert res.t.tolist() == [0.0, 0.25, 0.5, 0.75, 1.0]
    assert [s.time for s in res.statics] == [0.5]
    assert res.request(1)[2, :2] == pytest.approx([0.4 - 0.0981, 0.0], abs=1e-9)
    alone = _load(tmp_path / "moved.adm", simulate={"analysis_type": "TRANSIENT",
                                                    "end_time": 0.5, "print_interval": 0.25})
    transient = alone.run().request(1)
    np.testing.assert_array_equal(res.request(1)[:2], transient[:2])
    assert transient[2, :2] == pytest.approx([0.33769, 1.50004], abs=1e-4)
