"""The 3-D animation's data (pysolver/viewer): poses against the kernel's own request channels,
what is drawn for each element, and the page as one file that needs no network."""
import base64
import html
import json
import pickle
import re

import numpy as np
import pytest

import pysolver
from pysolver.deck.expr import parse
from pysolver.viewer import page, scene, shapes
from pysolver.viewer.poses import quaternion, rotations

from helpers import ROOT

GRAPHICS = ROOT / "tests" / "decks" / "graphics.xml"
README_DECK = ROOT / "decks" / "particle_between_lines.xml"


@pytest.fixture(scope="module")
def pendulum():
    model = pysolver.load(GRAPHICS)
    return model, model.run(progress=False)


def _close(a, b):
    """Equal to 1e-12 relative to the scene's lengths (metres here: 1e-12 m)."""
    scale = max(1.0, float(np.max(np.abs(b))))
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * scale)


def test_marker_positions_and_axes_equal_the_requests_at_every_row(pendulum):
    """The tip marker (off its body's centre of mass, turned by psi) is where DX/DY/DZ say at
    each of the 201 rows; the elbow seen in the tip's axes, DX/DY/DZ(22, 32, 32), checks the
    orientations of both links."""
    model, res = pendulum
    poses = res.animate(max_frames=None).scene.poses
    assert len(poses.t) == len(res.t) == 201
    _close(poses.marker_position(32), res.request(1)[:, :3])
    rel = np.einsum("ni,nij->nj", poses.marker_position(22) - poses.marker_position(32),
                    poses.marker_axes(32))
    _close(rel, res.request(2)[:, :3])
    assert np.ptp(res.request(1)[:, 2]) > 0.5      # the tip does move


def test_a_point_body_marker_equals_its_requests():
    model = pysolver.load(README_DECK)
    res = model.run(progress=False)
    poses = res.animate().scene.poses
    got = poses.marker_position(10)
    _close(got[:, 0], res.request(1)[:, 0])
    _close(got[:, 2], res.request(1)[:, 1])
    assert poses.rotation(2) is None and 2 not in poses.euler


def test_quaternions_are_the_unit_euler_parameters(pendulum):
    """The page's quaternions (x, y, z, w) are (e1, e2, e3, e0) of the states, normalized;
    quaternion() of a rotation matrix inverts rotations() (up to sign)."""
    model, res = pendulum
    sc = res.animate().scene
    data = sc.data()
    (link1,) = [b for b in data["bodies"] if b["id"] == 2]
    q = np.frombuffer(base64.b64decode(link1["quat"]), np.float32).reshape(-1, 4)
    col = res.state_names.index("body2.e0")
    e = res.y[:, col:col + 4] / np.linalg.norm(res.y[:, col:col + 4], axis=1)[:, None]
    np.testing.assert_allclose(q, np.column_stack([e[:, 1:], e[:, :1]]), atol=1e-7)
    for R in rotations(e[::50]):
        back = quaternion(R)
        np.testing.assert_allclose(rotations(np.array([[back[3], *back[:3]]]))[0], R,
                                   atol=1e-14)


def test_the_graphics_as_drawn(pendulum):
    """Each Post_Graphic becomes the shape its attributes say, on its marker; a TriaMesh is a
    note; both links carry graphics, so neither gets the generic glyph; the revolutes are
    pins on their J markers, the spring a coil from J to I."""
    model, res = pendulum
    sc = res.animate().scene
    by = {it["label"].split(" ")[1]: it for it in sc.items
          if it["label"].startswith("Post_Graphic")}
    assert by["1"] == {"kind": "cylinder", "marker": 23, "r0": 0.035, "r1": 0.035, "z0": 0.0,
                       "z1": 1.0, "open": False, "color": "#466eaa",
                       "label": "Post_Graphic 1"}
    assert (by["2"]["kind"], by["2"]["marker"], by["2"]["c"], by["2"]["s"]) == \
        ("box", 22, [0.0, 0.0, 0.0], [0.1, 0.1, 0.1])
    assert (by["3"]["kind"], by["3"]["markers"]) == ("polyline", [31, 32])
    assert (by["4"]["kind"], by["4"]["r"], by["4"]["marker"]) == ("sphere", 0.09, 32)
    assert (by["5"]["c"], by["5"]["s"]) == ([0.1, 0.1, 0.03], [0.2, 0.2, 0.06])
    assert (by["6"]["r0"], by["6"]["r1"], by["6"]["z1"]) == (0.06, 0.03, 0.15)
    assert "7" not in by
    assert sc.notes == ["Post_Graphic 7 (TriaMesh): not drawn: type TriaMesh is not drawn "
                        "(meshes, CAD files, curves and surfaces are not read)"]
    assert [b["glyph"] for b in sc.bodies] == [False, False]
    joints = [it for it in sc.items if it["label"].startswith("Constraint_Joint")]
    assert [(it["kind"], it["marker"]) for it in joints] == [("cylinder", 2), ("cylinder", 22)]
    (coil,) = [it for it in sc.items if it["kind"] == "coil"]
    assert coil["markers"] == [3, 32]


def test_glyphs_scale_with_the_scene():
    """The same deck in mm and in m: every size the view draws scales by 1000."""
    mm = pysolver.load(README_DECK).run(progress=False).animate().scene
    si = pysolver.load(ROOT / "decks" / "particle_between_lines_si.xml").run(progress=False)
    si = si.animate().scene
    assert (mm.length, si.length) == ("mm", "m")
    assert mm.radius == pytest.approx(1000 * si.radius, rel=1e-6)
    assert mm.glyph == pytest.approx(1000 * si.glyph, rel=1e-6)


def test_penalty_planes_of_the_readme_deck():
    """Force_Penalty 1 + x - z and 1 - x - z are the planes z = 1 + x and z = 1 - x: each
    patch's centre lies on its plane and its normal is the gradient's direction."""
    sc = pysolver.load(README_DECK).run(progress=False).animate().scene
    planes = [it for it in sc.items if it["kind"] == "plane"]
    assert [p["label"] for p in planes] == ["Force_Penalty 1 Enforce 1+x<=z",
                                            "Force_Penalty 2 Enforce 1-x<=z"]
    for p, a in zip(planes, ([1.0, 0, -1.0], [-1.0, 0, -1.0])):
        c = np.asarray(p["centre"])
        assert 1 + np.dot(a, c) == pytest.approx(0, abs=1e-9)
        normal = np.cross(p["u"], p["v"])
        np.testing.assert_allclose(np.abs(normal @ a) / np.linalg.norm(a), 1.0, rtol=1e-12)
        assert p["w"] >= 12 * sc.glyph and p["h"] >= 12 * sc.glyph


def test_affine_expressions():
    """Penalty expressions that are planes in one marker's position, and some that are not."""
    model = pysolver.load(README_DECK)
    c, mid, a = shapes.affine(parse("2*(3 - DZ(10))/4 + PI"), model)
    assert (c, mid) == (pytest.approx(1.5 + np.pi), 10)
    np.testing.assert_array_equal(a, [0, 0, -0.5])
    assert shapes.affine(parse("DX(10)*DZ(10)"), model) is None
    assert shapes.affine(parse("DM(10)"), model) is None
    assert shapes.affine(parse("DX(10, 10)"), model) is None     # relative to a moving marker


def test_params_that_move_markers_are_drawn_where_the_run_had_them(pendulum):
    """A run with the tip marker moved by params: the view's tip is the run's DX/DY/DZ, and
    the model's own records are back to the deck's afterwards."""
    model, _ = pendulum
    res = model.run(progress=False, params={"Reference_Marker/32/pos_x": 1.6})
    sc = res.animate(max_frames=None).scene
    _close(sc.poses.marker_position(32), res.request(1)[:, :3])
    assert model.markers[32].pos[0] == 1.8
    assert model.compile().model.markers[32].pos[0] == 1.8


def test_a_result_without_its_model():
    """A pickled Result leaves its model behind; animate then asks for it."""
    model = pysolver.load(README_DECK)
    res = pickle.loads(pickle.dumps(model.run(progress=False)))
    with pytest.raises(ValueError, match=r"pass it, res\.animate\(model\)"):
        res.animate()
    assert len(res.animate(model).scene.poses.t) == len(res.t)


def test_rows_kept():
    import inspect
    assert inspect.signature(pysolver.Result.animate).parameters["max_frames"].default == \
        scene.MAX_FRAMES
    np.testing.assert_array_equal(scene.rows_kept(5, 10), np.arange(5))
    np.testing.assert_array_equal(scene.rows_kept(10, 4), [0, 3, 6, 9])
    np.testing.assert_array_equal(scene.rows_kept(11, 4), [0, 4, 8, 10])
    with pytest.raises(ValueError, match="max_frames must be at least 2"):
        scene.rows_kept(11, 1)
    res = pysolver.load(README_DECK).run(progress=False)
    sc = res.animate(max_frames=100).scene
    assert (len(sc.poses.t), sc.total) == (87, 601)
    np.testing.assert_array_equal(sc.poses.t, res.t[np.r_[0:600:7, 600]])


def test_thinned_frames_are_a_note_of_the_page_and_of_animation_notes():
    """A 4001-row run keeps 2001 frames: the note is Animation.notes' first entry and the
    page's (its data's notes, which the page lists as they are); every k-th in words."""
    text = README_DECK.read_text().replace('print_interval="0.005"', 'print_interval="0.00075"')
    res = pysolver.loads(text).run(progress=False)
    anim = res.animate()
    assert (len(res.t), len(anim.scene.poses.t)) == (4001, 2001)
    assert anim.notes == ["showing 2001 of 4001 output rows (every 2nd)"]
    data = json.loads(re.search(r'id="scene-data">(.*?)</script>', anim.html(), re.S).group(1))
    assert data["notes"] == anim.notes
    few = pysolver.load(README_DECK).run(progress=False)
    assert few.animate(max_frames=100).notes == \
        ["showing 87 of 601 output rows (every 7th and the last)"]
    assert few.animate(max_frames=301).notes == ["showing 301 of 601 output rows (every 2nd)"]
    assert few.animate(max_frames=201).notes == ["showing 201 of 601 output rows (every 3rd)"]
    assert few.animate().notes == [] and few.animate(max_frames=None).notes == []
    assert [scene.ordinal(k) for k in (1, 2, 3, 4, 11, 12, 13, 21, 22, 23, 101, 111, 112, 122)] \
        == ["1st", "2nd", "3rd", "4th", "11th", "12th", "13th", "21st", "22nd", "23rd",
            "101st", "111th", "112th", "122nd"]
    js = (page.HERE / "viewer.js").read_text(encoding="utf-8")
    assert "'showing " not in js            # the page words no note of its own


def test_thinned_frames_come_first_among_the_notes(pendulum):
    """A deck with notes of elements not drawn: the rows kept first, then those."""
    model, res = pendulum
    notes = res.animate(max_frames=50).notes
    assert notes[0] == "showing 41 of 201 output rows (every 5th)"
    assert notes[1:] == res.animate().notes and len(notes) == 2


def test_the_page_is_one_file_without_network(pendulum, tmp_path):
    """No src= or href= to anything; three.js, the data and the script inlined; the scene's
    data parse back; Jupyter gets it as an iframe's srcdoc."""
    model, res = pendulum
    anim = res.animate()
    path = anim.save(tmp_path / "scene.html")
    text = open(path, encoding="utf-8").read()
    assert not re.search(r"<(script|link|img|iframe)[^>]*\s(src|href)\s*=", text, re.I)
    assert text.count("<script") == 3 and "THREE" in text
    data = json.loads(re.search(r'<script type="application/json" id="scene-data">(.*?)'
                                r"</script>", text, re.S).group(1))
    assert (data["title"], data["n"], data["length"]) == ("graphics.xml", 201, "m")
    frame = anim._repr_html_()
    assert frame.startswith('<iframe srcdoc="')
    assert html.unescape(re.search(r'srcdoc="(.*?)"', frame, re.S).group(1)) == text


def test_the_vendored_three_is_what_its_readme_says():
    vendor = page.HERE / "vendor"
    bundle = (vendor / "three.min.js").read_text(encoding="utf-8")
    revision = page.THREE_VERSION.split(".")[1]
    assert re.search(r'="%s"' % revision, bundle)              # THREE.REVISION
    assert "OrbitControls" in bundle and "</script" not in bundle.lower()
    assert (vendor / "LICENSE").read_text(encoding="utf-8").startswith(
        "The MIT License\n\nCopyright © 2010-2026 three.js authors")
    assert f"THREE={page.THREE_VERSION}" in (vendor / "fetch.sh").read_text()
    assert page.THREE_VERSION in (vendor / "README.md").read_text()


def test_pysolver_run_writes_scene_html_unless_told_not_to(tmp_path):
    from pysolver.cli import main
    out = tmp_path / "out"
    assert main(["run", str(README_DECK), "-o", str(out), "-q", "--no-plot"]) == 0
    text = (out / "scene.html").read_text(encoding="utf-8")
    assert '"title":"particle_between_lines.xml"' in text and '"n":601' in text
    bare = tmp_path / "bare"
    assert main(["run", str(README_DECK), "-o", str(bare), "-q", "--no-plot",
                 "--no-animation"]) == 0
    assert sorted(p.name for p in bare.iterdir()) == ["requests.csv", "stats.json"]


@pytest.mark.parametrize("processes", [0, 1])
def test_a_sweep_case_is_drawn_with_its_numbers(pendulum, processes):
    """sweep.result(i) knows its model and case, in this process or from a worker's pickle:
    the tip drawn where that case's run had it."""
    model, _ = pendulum
    study = pysolver.sweep(model, [{"Reference_Marker/32/pos_x": 1.5}], processes=processes)
    res = study.result(0)
    _close(res.animate(max_frames=None).scene.poses.marker_position(32), res.request(1)[:, :3])
    assert res.request(1)[0, 0] == pytest.approx(1.5)


def test_non_finite_rows_do_not_break_the_page(pendulum):
    """A run that failed on a NaN keeps rows with non-finite states: the page is still made,
    its sizes from the finite rows."""
    model, res = pendulum
    broken = pickle.loads(pickle.dumps(res))
    broken.y[-5:] = np.nan
    anim = broken.animate(model)
    assert anim.scene.radius == pytest.approx(res.animate().scene.radius, rel=0.05)
    data = json.loads(re.search(r'id="scene-data">(.*?)</script>', anim.html(), re.S).group(1))
    assert data["n"] == len(res.t)


def test_each_joint_type_is_drawn_as_its_table_says():
    """The shapes of every joint type (tests/decks/all_joints.xml, lead_joints.xml), on I's
    or J's marker, as docs/animation.md lists them; FREE holds nothing and has none."""
    drawn = {}
    for deck in ("all_joints.xml", "lead_joints.xml"):
        model = pysolver.load(ROOT / "tests" / "decks" / deck)
        for it in model.run(progress=False).animate().scene.items:
            if it["label"].startswith("Constraint_Joint"):
                jo = model.joints[int(it["label"].split()[1])]
                drawn.setdefault(jo.type, []).append(
                    (it["kind"], "J" if it["marker"] == jo.j else "I"))
    pins, axes = [("cylinder", "J"), ("cylinder", "I")], [("axis", "J"), ("axis", "I")]
    assert drawn == {
        "REVOLUTE": [("cylinder", "J")] * 2, "SPHERICAL": [("sphere", "I")],
        "ATPOINT": [("sphere", "I")], "FIXED": [("box", "I")],
        "TRANSLATIONAL": [("cylinder", "J"), ("box", "I")] * 2, "CYLINDRICAL": pins * 2,
        "UNIVERSAL": pins, "HOOKE": pins, "CONSTANT_VELOCITY": pins,
        "PLANAR": [("square", "J"), ("sphere", "I")], "INPLANE": [("square", "J"), ("sphere", "I")],
        "INLINE": [("axis", "J"), ("sphere", "I")], "ORIENTATION": axes, "PARALLEL_AXES": axes,
        "PERPENDICULAR": axes, "SCREW": [("cylinder", "J"), ("helix", "J"), ("cylinder", "I")],
        "RACK_PINION": pins}


def test_a_translational_rail_spans_the_slider_travel():
    """The slider-crank's rail runs along zJ over DZ(42, 3, 3) of the run (its channel 7), two
    glyphs more at each end; the pinned joints' pins are 3 glyphs long."""
    model = pysolver.load(ROOT / "decks" / "joints" / "slider_crank.xml")
    res = model.run(progress=False)
    sc = res.animate().scene
    (rail,) = [it for it in sc.items if it["label"].startswith("Constraint_Joint 4")
               and it["kind"] == "cylinder"]
    dz = res.request(1)[:, 6]
    assert rail["marker"] == 3
    assert rail["z0"] == pytest.approx(dz.min() - 2 * sc.glyph, abs=1e-12)
    assert rail["z1"] == pytest.approx(dz.max() + 2 * sc.glyph, abs=1e-12)
    (pin,) = [it for it in sc.items if it["label"].startswith("Constraint_Joint 2")]
    assert pin["z1"] - pin["z0"] == pytest.approx(3 * sc.glyph)


def test_sensor_events_and_a_failed_run_are_on_screen():
    """Sensor firings become ticks on the slider (their times and sensors); a failed run's
    page says so with its message; a deck from text is titled so."""
    model = pysolver.load(ROOT / "decks" / "sensor_halt_acceleration.xml")
    res = model.run(progress=False)
    data = res.animate().scene.data()
    assert [e["t"] for e in data["events"]] == list(res.t_events) and len(res.events) >= 1
    assert data["events"][0]["label"].startswith(f"Sensor_Event {res.events[0].sensor}")
    failed = pickle.loads(pickle.dumps(res))
    failed.success, failed.message = False, "IDA failed: the corrector did not converge"
    assert failed.animate(model).scene.data()["status"] == {
        "success": False, "message": "IDA failed: the corrector did not converge"}
    text = pysolver.loads(README_DECK.read_text())
    assert text.run(progress=False).animate().scene.title == "deck text"


def test_graphics_by_adams_keywords_and_the_other_types():
    """The Adams GRAPHICS keywords (lower case in a dataset's attributes) and the types the
    double pendulum lacks, read as docs/animation.md's table says; bad ones are notes."""
    from pysolver.records import Graphic
    model = pysolver.load(README_DECK)
    poses = model.run(progress=False).animate().scene.poses

    def draw(kind, **attrs):
        (it,) = shapes.graphic(Graphic(7, kind, {k: str(v) for k, v in attrs.items()}),
                               model.markers, poses, 2.0)
        return {k: v for k, v in it.items() if k not in ("color", "label")}

    assert draw("CYLINDER", cm=10, length=-5, radius=1) == dict(
        kind="cylinder", marker=10, r0=1.0, r1=1.0, z0=0.0, z1=-5.0, open=False)
    assert draw("FRUSTUM", cm=10, length=4, top=1, bottom=2) == dict(
        kind="cylinder", marker=10, r0=2.0, r1=1.0, z0=0.0, z1=4.0, open=False)
    assert draw("BOX", corner=1, x=2, y=-4, z=6) == dict(kind="box", marker=1,
                                                         c=[1.0, -2.0, 3.0], s=[2.0, 4.0, 6.0])
    assert draw("ELLIPSOID", cm=10, xscale=4, yscale=2, zscale=1) == dict(
        kind="sphere", marker=10, c=[0, 0, 0], r=2.0, scale=[1.0, 0.5, 0.25])
    assert draw("CIRCLE", cm=1, rm=10) == dict(kind="arc", marker=1, r=pytest.approx(
        np.hypot(100, 120)), a0=0.0, a1=2 * np.pi)
    assert draw("ARC", cm=1, radius=3, rangle=1.5) == dict(kind="arc", marker=1, r=3.0,
                                                           a0=0.0, a1=1.5)
    assert draw("OUTLINE", outline="1, 10 1") == dict(kind="polyline", markers=[1, 10, 1])
    assert draw("SPDP", i=10, j=1, da=3, coils=5) == dict(kind="coil", markers=[10, 1],
                                                          r=1.5, turns=5.0)
    assert draw("Point", marker_id=10) == dict(kind="sphere", marker=10, c=[0, 0, 0], r=0.6,
                                               scale=[1, 1, 1])
    for kind, attrs, why in [
            ("CYLINDER", {"cm": 99, "length": 1, "radius": 1}, "cm: marker 99 does not exist"),
            ("Sphere", {"center_marker_id": 10, "radius": "big"}, "radius='big' is not a number"),
            ("Sphere", {"center_marker_id": 10}, "no radius"),
            ("OUTLINE", {"outline": "10"}, "an outline joins two markers or more"),
            ("ELLIPSOID", {"cm": 10, "xscale": 0, "yscale": 1, "zscale": 1},
             "its diameters must be > 0, got [0.0, 1.0, 1.0]"),
            ("TORUS", {"cm": 10}, "type TORUS is not drawn (meshes, CAD files, curves and "
                                  "surfaces are not read)")]:
        with pytest.raises(shapes.Skip) as err:
            shapes.graphic(Graphic(7, kind, attrs), model.markers, poses, 2.0)
        assert str(err.value) == why


@pytest.mark.parametrize("unit, seconds", [("SECOND", 1.0), ("MILLISECOND", 1e-3),
                                           ("MINUTE", 60.0)])
def test_the_scene_data_carries_seconds_per_time_unit(unit, seconds):
    """The page's speed menu counts in real time from it (tests/test_viewer_browser.py reads
    the menu Chromium builds)."""
    text = README_DECK.read_text().replace('time="SECOND"', f'time="{unit}"').replace(
        'end_time="3.0"', 'end_time="0.01"')
    assert f'time="{unit}"' in text
    data = pysolver.loads(text).run(progress=False).animate().scene.data()
    assert data["seconds"] == seconds
    assert data["time"] == {"SECOND": "s", "MILLISECOND": "ms", "MINUTE": "min"}[unit]


@pytest.mark.parametrize("kw, error, message", [
    ({"max_frames": 2.5}, TypeError, "max_frames must be an int (at least 2) or None, got 2.5 "
                                     "(float)"),
    ({"max_frames": "10"}, TypeError, "max_frames must be an int (at least 2) or None, got "
                                      "'10' (str)"),
    ({"max_frames": True}, TypeError, "max_frames must be an int (at least 2) or None, got "
                                      "True (bool)"),
    ({"max_frames": 1}, ValueError, "max_frames must be at least 2 (the first and the last "
                                    "row), got 1"),
    ({"max_frames": 0}, ValueError, "max_frames must be at least 2 (the first and the last "
                                    "row), got 0"),
    ({"model": 5}, TypeError, "animate() takes the Model that made the run, not 5 (int)"),
    ({"params": "abc"}, TypeError, "params must be a dict {path: number} or None, got 'abc' "
                                   "(str)"),
    ({"params": [1]}, TypeError, "params must be a dict {path: number} or None, got [1] "
                                 "(list)"),
])
def test_animate_arguments_of_the_wrong_kind_are_named(kw, error, message):
    """Trial 44, defect 4: max_frames=2.5 was an IndexError from NumPy and "10" a
    comparison's TypeError; the check holds for a run shorter than max_frames too."""
    res = pysolver.loads(README_DECK.read_text().replace('end_time="3.0"', 'end_time="0.05"'))\
        .run(progress=False)
    assert len(res.t) == 11
    with pytest.raises(error) as err:
        res.animate(**kw)
    assert str(err.value) == message
    assert len(res.animate(max_frames=np.int64(5)).scene.poses.t) == 5


def test_run_params_that_are_no_dict_are_a_type_error():
    model = pysolver.load(README_DECK)
    with pytest.raises(TypeError) as err:
        model.run(params=[("Force_Penalty/1/penalty", 2e4)])
    assert str(err.value) == ("params must be a dict {path: number}, got "
                              "[('Force_Penalty/1/penalty', 20000.0)] (list)")
