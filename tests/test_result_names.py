"""Every column of a Result has a name of its own (channels that share a name are qualified by
their request) in res.columns(), the CSV header saved and streamed, the DataFrame, res.units
and res.quantities, stats.json and the plot; the accessors take msolve elements and labels
and say what the run has when they are given something else; a figure with nothing to plot
says so."""
import json
import pickle

import numpy as np
import pytest

import pysolver
from pysolver.cli import main
from pysolver.msolve import (
    Accgrav,
    Joint,
    Marker,
    Model,
    Motion,
    Part,
    Request,
    SpringDamper,
    Units,
)
from pysolver.naming import column_names

#: The trial's scene (trial 43, item 6): a falling part in mm with a VELOCITY request, an
#: expression request whose channel is named vz (a length), and two DISPLACEMENT requests.
SHARED = '''
from pysolver.msolve import *
model = Model(); Units(length="MILLIMETER"); Accgrav(kgrav=-9810)
ground = Part(ground=True)
p = Part(mass=2.0, ip=[1, 1, 1], vz=1000); p.cm = Marker(part=p, qp=[0, 0, 5])
Request(type="VELOCITY", i=p.cm, label="P_vel")
Request(f1=f"DZ({p.cm.id})", cnames=["vz"], label="height")
Request(type="DISPLACEMENT", i=p.cm)
Request(type="DISPLACEMENT", i=p.cm, comment="again")
model.simulate(type="DYNAMICS", end=0.1, steps=2)
'''

HEADER = ["time [s]", "vm [mm/s]", "vx [mm/s]", "vy [mm/s]", "vz (request 1) [mm/s]",
          "wm [rad/s]", "wx [rad/s]", "wy [rad/s]", "wz [rad/s]", "vz (request 2) [mm]"] + [
    f"{c} (request {r}) [{'rad' if c in ('psi', 'theta', 'phi') else 'mm'}]"
    for r in (3, 4) for c in ("mag", "x", "y", "z", "psi", "theta", "phi")]


@pytest.fixture(scope="module")
def shared(tmp_path_factory):
    path = tmp_path_factory.mktemp("shared") / "shared.py"
    path.write_text(SHARED)
    return path, pysolver.load(path)


def _pendulum():
    """A rod on a labelled revolute, driven by a labelled motion, with a labelled request."""
    model = Model()
    Accgrav(jgrav=-9.81)
    ground = Part(ground=True)
    o = Marker(body=ground)
    b = Part(mass=1, ip=[0.1] * 3)
    b.cm = Marker(body=b, qp=[1, 0, 0])
    J = Joint(type="REVOLUTE", i=Marker(body=b), j=o, label="hinge")
    M = Motion(joint=J, jtype="ROTATION", function="TIME", label="drive")
    R = Request(type="DISPLACEMENT", i=b.cm, label="disp")
    res = model.simulate(type="DYNAMICS", end=1, steps=50)
    return res, J, M, R, b


@pytest.fixture(scope="module")
def pendulum():
    return _pendulum()


# --- column names --------------------------------------------------------------------------

def test_the_naming_rule():
    labels = {(1, 0): "x", (1, 1): "z", (2, 0): "x", (2, 1): "y", (3, 0): "time",
              (4, 0): "x (request 2)", (5, 0): "a", (5, 1): "a"}
    keys = [(1, 0), (1, 1), (2, 0), (2, 1), (2, 2), (3, 0), (4, 0), (5, 0), (5, 1)]
    assert column_names(keys, labels) == [
        "x (request 1)", "z", "x (request 2) #2", "y", "REQ2.3", "time (request 3)",
        "x (request 2)", "a (request 5, channel 1)", "a (request 5, channel 2)"]
    # names that do not repeat stay as they are
    assert column_names([(1, 0), (1, 1), (2, 3)], {(1, 0): "x", (1, 1): "z"}) == \
        ["x", "z", "REQ2.4"]


def test_shared_names_are_qualified_everywhere(shared, tmp_path):
    path, model = shared
    res = model.run(stream=tmp_path / "streamed.csv")
    names, table = res.columns(units=True)
    assert names == HEADER
    assert res.columns()[0] == [n.rsplit(" [", 1)[0] for n in HEADER]
    assert len(set(names)) == len(names)
    # one unit and one kind per column: the second vz is a length, not the first's mm/s
    assert res.units["vz (request 1)"] == "mm/s" and res.units["vz (request 2)"] == "mm"
    assert res.quantities["vz (request 1)"] == "velocity"
    assert res.quantities["vz (request 2)"] == "length"
    assert res.units["psi (request 4)"] == "rad" and "vz" not in res.units
    assert list(res.units) == res.columns()[0]
    assert list(res.quantities) == res.columns()[0]
    np.testing.assert_array_equal(table[:, 9], res.request(2)[:, 0])
    # the CSV saved and streamed: the same header, the same bytes
    res.save(tmp_path / "saved.csv")
    for name in ("saved.csv", "streamed.csv"):
        assert (tmp_path / name).read_text().splitlines()[0] == ",".join(HEADER)
    assert (tmp_path / "saved.csv").read_bytes() == (tmp_path / "streamed.csv").read_bytes()
    res.save(tmp_path / "r.npz")
    with np.load(tmp_path / "r.npz") as npz:
        assert list(npz["table_columns"]) == HEADER


def test_the_dataframe_has_one_column_per_channel(shared):
    pytest.importorskip("pandas", reason="pandas is not installed")
    res = shared[1].run()
    df = res.to_dataframe()
    assert list(df.columns) == HEADER[1:] and df.columns.is_unique
    assert df["x (request 3) [mm]"].ndim == 1          # not a frame of two x columns
    np.testing.assert_array_equal(df["vz (request 2) [mm]"].to_numpy(), res.request(2)[:, 0])
    np.testing.assert_array_equal(df["z (request 4) [mm]"].to_numpy(), res.request(4)[:, 3])
    assert df.attrs["units"] == res.units and df.attrs["quantities"] == res.quantities


def test_the_command_line_writes_the_same_names(shared, tmp_path, capsys):
    path, _ = shared
    assert main(["run", str(path), "-o", str(tmp_path), "-q", "--no-plot",
                 "--no-animation"]) == 0
    capsys.readouterr()
    assert (tmp_path / "requests.csv").read_text().splitlines()[0] == ",".join(HEADER)
    units = json.loads((tmp_path / "stats.json").read_text())["units"]
    assert units["vz (request 1)"] == "mm/s" and units["vz (request 2)"] == "mm"
    assert len(units) == len(HEADER)


def test_the_plot_legends_use_the_column_names(shared):
    pytest.importorskip("matplotlib", reason="matplotlib is not installed")
    fig = shared[1].run().plot()
    legends = {ax.get_ylabel(): [t.get_text() for t in ax.get_legend().get_texts()]
               for ax in fig.axes}
    assert legends["velocity [mm/s]"] == ["vm", "vx", "vy", "vz (request 1)"]
    assert legends["length [mm]"][0] == "vz (request 2)"
    assert "x (request 4)" in legends["length [mm]"]


def test_names_that_do_not_repeat_are_kept(pendulum):
    res = pendulum[0]
    assert res.columns()[0] == ["time", "mag", "x", "y", "z", "psi", "theta", "phi"]
    assert res.units == {"time": "s", "mag": "m", "x": "m", "y": "m", "z": "m",
                         "psi": "rad", "theta": "rad", "phi": "rad"}


# --- accessors -----------------------------------------------------------------------------

def test_the_accessors_take_elements_labels_and_ids(pendulum):
    res, J, M, R, _ = pendulum
    for key in (J, "hinge", 1, np.int64(1)):
        np.testing.assert_array_equal(res.joint(key), res.joint(1))
    np.testing.assert_array_equal(res.joint(J, 1), res.joint(1, 1))
    for key in (M, "drive"):
        np.testing.assert_array_equal(res.motion(key), res.motion(1))
    for key in (R, "disp"):
        np.testing.assert_array_equal(res.request(key), res.request(1))
    assert res.joint_ids == [1] and res.motion_ids == [1] and res.request_ids == [1]
    assert res.joint(J)[10, 2] != 0.0


@pytest.mark.parametrize("call, kind, message", [
    (lambda r, e: r.joint(-1), KeyError, "no Constraint_Joint -1 (joints: 1 'hinge')"),
    (lambda r, e: r.joint(2), KeyError, "no Constraint_Joint 2 (joints: 1 'hinge')"),
    (lambda r, e: r.joint("hing"), KeyError,
     "no Constraint_Joint labelled 'hing' (joints: 1 'hinge')"),
    (lambda r, e: r.joint("drive"), KeyError,
     "no Constraint_Joint labelled 'drive' (joints: 1 'hinge')"),
    (lambda r, e: r.request(5), KeyError, "no Post_Request 5 (requests: 1 'disp')"),
    (lambda r, e: r.motion(2), KeyError, "no motion 2 (motions: 1 'drive')"),
    (lambda r, e: r.controller(1), KeyError, "no LoadControl 1 (tasks: none)"),
    (lambda r, e: r.joint(e["M"]), TypeError,
     "res.joint takes a Constraint_Joint id (int), the Joint or Jprim object or its label "
     "(str); got a Motion (id 1)"),
    (lambda r, e: r.request(e["b"]), TypeError,
     "res.request takes a Post_Request id (int), the Request object or its label (str); "
     "got a Part (id 2)"),
    (lambda r, e: r.motion(1.0), TypeError,
     "res.motion takes a motion id (int), the Motion object or its label (str); got float 1.0"),
    (lambda r, e: r.joint(None), TypeError,
     "res.joint takes a Constraint_Joint id (int), the Joint or Jprim object or its label "
     "(str); got None"),
    (lambda r, e: r.joint(True), TypeError,
     "res.joint takes a Constraint_Joint id (int), the Joint or Jprim object or its label "
     "(str); got bool True"),
])
def test_one_clear_error_naming_what_the_run_has(pendulum, call, kind, message):
    res, J, M, R, b = pendulum
    with pytest.raises(kind) as err:
        call(res, {"M": M, "b": b})
    assert err.value.args == (message,)


def test_a_label_two_elements_share_asks_for_the_id():
    model = Model()
    Part(ground=True)
    b = Part(mass=1, ip=[1] * 3)
    b.cm = Marker(body=b)
    Request(type="DISPLACEMENT", i=b.cm, label="disp")
    Request(type="VELOCITY", i=b.cm, label="disp")
    res = model.simulate(type="DYNAMICS", end=0.1, steps=2)
    with pytest.raises(KeyError) as err:
        res.request("disp")
    assert err.value.args == ("the label 'disp' names Post_Request 1 and 2: pass the id",)


def test_labels_survive_a_pickle_and_an_old_pickle_takes_ids(pendulum):
    res = pickle.loads(pickle.dumps(pendulum[0]))
    np.testing.assert_array_equal(res.joint("hinge"), pendulum[0].joint(1))
    del res.__dict__["_element_labels"]          # a Result pickled before labels were kept
    np.testing.assert_array_equal(res.joint(1), pendulum[0].joint(1))
    with pytest.raises(KeyError) as err:
        res.joint("hinge")
    assert err.value.args == ("no Constraint_Joint labelled 'hinge' (joints: 1)",)


# --- a figure with nothing to plot ---------------------------------------------------------

def _texts(fig):
    return [t.get_text() for ax in fig.axes for t in ax.texts]


def test_a_run_without_requests_says_there_is_nothing_to_plot(tmp_path):
    pytest.importorskip("matplotlib", reason="matplotlib is not installed")
    model = Model()
    Accgrav(jgrav=-9.81)
    ground = Part(ground=True)
    o = Marker(body=ground)
    b = Part(mass=1, ip=[0.1] * 3)
    b.cm = Marker(body=b, qp=[1, 0, 0])
    J = Joint(type="REVOLUTE", i=Marker(body=b), j=o, label="hinge")
    Motion(joint=J, jtype="ROTATION", function="TIME")
    res = model.simulate(type="DYNAMICS", end=1, steps=10)
    fig = res.plot(tmp_path / "r.png")
    assert (tmp_path / "r.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(fig.axes) == 1 and not fig.axes[0].axison
    assert _texts(fig) == ["nothing to plot: this run has no request channels\n"
                           "add a Post_Request (msolve: Request) for what to plot\n"
                           "joint reactions: res.joint(id), joints 1\n"
                           "motion reactions: res.motion(id), motions 1\n"
                           "states: res.y, columns named by res.state_names"]
    assert fig._suptitle.get_text() == "test_result_names.py"    # the script that built it


def test_a_free_body_without_requests_names_its_states():
    pytest.importorskip("matplotlib", reason="matplotlib is not installed")
    model = Model()
    Units(length="MILLIMETER")
    Part(ground=True)
    b = Part(mass=1, ip=[1] * 3, vx=1)
    b.cm = Marker(body=b)
    fig = model.simulate(type="DYNAMICS", end=1, steps=5).plot()
    assert _texts(fig) == ["nothing to plot: this run has no request channels\n"
                           "add a Post_Request (msolve: Request) for what to plot\n"
                           "states: res.y, columns named by res.state_names"]


def test_a_static_run_without_requests_keeps_its_title_and_says_so():
    pytest.importorskip("matplotlib", reason="matplotlib is not installed")
    model = Model()
    Accgrav(kgrav=-9.81)
    ground = Part(ground=True)
    o = Marker(body=ground, qp=[0, 0, 2])
    b = Part(mass=1, ip=[0.1] * 3)
    b.cm = Marker(body=b, qp=[0, 0, 1])
    SpringDamper(type="TRANSLATION", i=b.cm, j=o, k=100.0, c=1.0, length=1.0)
    fig = model.simulate(type="STATICS").plot()
    assert len(fig.axes) == 1
    assert fig.axes[0].get_title().startswith("static equilibrium at t = 0: FIM_S, 2 iterations")
    assert _texts(fig) == ["nothing to plot: this run has no request channels\n"
                           "add a Post_Request (msolve: Request) for what to plot\n"
                           "states: res.y, columns named by res.state_names"]
