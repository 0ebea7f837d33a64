"""pysolver convert in every direction (MotionSolve XML, Python statement scripts, Adams
datasets with their command files, scripts of msolve classes): every example deck's forms in
decks/forms/adams and decks/forms/msolve are what convert writes, build the same model number for
number (a marker given by its axes to rounding: REULER) and give the same results; a deck of every attribute the examples leave out makes
the round trip through each format and back; what a format cannot hold is a DeckError."""
import dataclasses
import importlib.util
import os
import shutil
import warnings

import numpy as np
import pytest

import pysolver
from pysolver import DeckError, DeckWarning, catalogue
from pysolver.cli import main
from pysolver.convert import convert

from helpers import DECKS, TEST_DECKS


def _module(path):
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


MAKE = _module(DECKS / "forms" / "make.py")
EVERY = TEST_DECKS / "forms" / "every_attribute.xml"


def _load(path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeckWarning)
        return pysolver.load(path, **kw)


def _tree(value):
    """An expression tree without the columns its nodes carry (where the text had them)."""
    if isinstance(value, tuple) and value and value[0] == "call":
        return ("call", value[1], [_tree(v) for v in value[2]])
    if isinstance(value, tuple) and value and value[0] == "name":
        return value[:2]
    if isinstance(value, (tuple, list)):
        return type(value)(_tree(v) for v in value)
    return value


#: What a dataset (and a script of msolve classes) holds to rounding, not bit for bit: a
#: marker given by the nine numbers of its axes is written with its 3-1-3 angles (REULER,
#: docs/adams.md "Writing datasets"), and so is what its axes turn (a body's inertia about
#: its IM marker's axes, a velocity along its VM marker's).
ROUNDED = ("rot", "im_rot", "inertia", "vel", "omega")


def _differences(a, b, path, rounded=False):
    """Where two parts of a model differ, numbers bit for bit (a zero's sign too), or with
    `rounded` the arrays of ROUNDED to 2e-15 of their largest entry; the expressions'
    texts and the deck locations aside."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if rounded and path.rpartition(".")[2] in ROUNDED and a.shape == b.shape:
            same = np.abs(a - b).max() <= 2e-15 * np.abs(a).max()
        else:
            same = a.shape == b.shape and np.array_equal(a, b, equal_nan=True) and \
                (a.dtype.kind != "f" or np.array_equal(np.signbit(a), np.signbit(b)))
        return [] if same else [f"{path}: {a!r} != {b!r}"]
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        return [d for f in dataclasses.fields(a) if f.name not in ("text", "texts", "line",
                                                                   "file", "load_text")
                for d in _differences(getattr(a, f.name), getattr(b, f.name),
                                      f"{path}.{f.name}", rounded)]
    if isinstance(a, dict):
        if list(a) != list(b):
            return [f"{path}: {list(a)} != {list(b)}"]
        return [d for k in a for d in _differences(a[k], b[k], f"{path}[{k}]", rounded)]
    if isinstance(a, tuple) and a and a[0] in ("call", "name"):
        a, b = _tree(a), _tree(b)
    if isinstance(a, (list, tuple)):
        if not isinstance(b, (list, tuple)) or len(a) != len(b):
            return [f"{path}: {a!r} != {b!r}"]
        return [d for k, (u, v) in enumerate(zip(a, b))
                for d in _differences(u, v, f"{path}[{k}]", rounded)]
    if callable(a):
        return []
    if type(a) is not type(b) or (a != b and a == a) or \
            (isinstance(a, float) and np.signbit(a) != np.signbit(b)):
        return [f"{path}: {a!r} != {b!r}"]
    return []


def model_differences(a, b, rounded=False):
    """Every difference between two models' elements, units, gravity, settings, commands
    (`rounded`: marker axes to rounding, as _differences)."""
    out = [d for el in catalogue.ELEMENTS
           for d in _differences(getattr(a, el.table), getattr(b, el.table), el.table,
                                 rounded)]
    for attr in ("units", "force_scale", "gravity", "static", "commands", "output_settings"):
        out += _differences(getattr(a, attr), getattr(b, attr), attr)
    return out + _differences(vars(a.transient), vars(b.transient), "transient")


def _rel(a, b):
    """Largest difference of two request tables over each channel's largest value (>= 1)."""
    assert np.array_equal(np.isnan(a), np.isnan(b))        # the same unused channels
    used = ~np.all(np.isnan(b), axis=0)
    a, b = a[:, used], b[:, used]
    if not a.size:
        return 0.0
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b).max(axis=0))))


def _same_results(res, ref, tol=1e-12):
    """Same success and message, same output rows, every request channel equal to `tol` of
    its scale at every row."""
    assert (res.success, res.status, res.message) == (ref.success, ref.status, ref.message)
    assert len(res.t) == len(ref.t)
    assert _rel(res.t[:, None], ref.t[:, None]) <= 1e-12
    assert res.request_ids == ref.request_ids
    for rid in ref.request_ids:
        assert _rel(res.request(rid), ref.request(rid)) <= tol, rid


def _runs_alike(model, res, ref_model, ref):
    """A form's run `res` is its deck's `ref`: to 1e-12 of scale when the two models are the
    same number for number; else (marker axes to rounding: IDA's steps may differ) to the
    integration error, both run at integr_tol 1e-10 (iftomm_a05_flyball, 10 s: 3e-8)."""
    if model_differences(ref_model, model) == []:
        _same_results(res, ref)
    else:
        ref, run = (m.run(progress=False, integr_tol=1e-10) for m in (ref_model, model))
        _same_results(run, ref, 1e-6)


#: Decks run for a fraction of their time here: IFToMM A02 (81 links) for 2 s of its 20 s.
SHORT = {"iftomm_a02_fourbar": 2.0, "iftomm_a02_fourbar_inline": 2.0}


def _forms_of(deck, sub):
    """The deck, its Python statement twin when it has one, its .adm (with the .acf beside)
    and its script of msolve classes."""
    twin = deck.with_suffix(".py")
    return [deck] + ([twin] if deck.suffix == ".xml" and twin.exists() else []) + \
        list(MAKE.outputs(deck, sub))


@pytest.mark.parametrize("deck, sub", MAKE.sources(),
                         ids=[f"{s}/{d.name}".lstrip("/") for d, s in MAKE.sources()])
def test_every_form_of_an_example_deck_builds_the_same_model_and_runs_alike(deck, sub):
    paths = _forms_of(deck, sub)
    simulate = {"analysis_type": "TRANSIENT", "end_time": SHORT[deck.stem],
                "print_interval": 0.05} if deck.stem in SHORT else None
    models = [_load(p, simulate=simulate) for p in paths]
    for path, model in zip(paths[1:], models[1:]):
        assert model_differences(models[0], model, rounded="forms" in path.parts) == [], path
    results = [m.run(progress=False) for m in models]
    assert results[0].success, results[0].message
    for model, res in zip(models[1:], results[1:]):
        _runs_alike(model, res, models[0], results[0])


def test_the_committed_forms_are_what_convert_writes():
    """decks/forms/make.py regenerates them: run it after changing a deck or a writer."""
    written = MAKE.all_forms()
    for path, text in written.items():
        assert path.exists(), f"{path} is missing: run python decks/forms/make.py"
        assert path.read_text() == text, f"{path} is out of date: run python decks/forms/make.py"
    shipped = {p for folder in ("adams", "msolve") for p in (DECKS / "forms" / folder).rglob("*")
               if p.is_file()}
    assert shipped == set(written), "decks/forms holds files make.py does not write"


# every_attribute.xml gives print_increment, which draws its DeckWarning
@pytest.mark.filterwarnings("ignore::pysolver.errors.DeckWarning")
def test_every_attribute_makes_the_round_trip_through_every_format(tmp_path):
    """Orientation forms, references, one-body forces, user subroutine scripts (named
    relative to the new folder), a Sensor_Evaluate of its own, request names with gaps,
    a spline surface, output settings, every integrator and statics setting, commands with
    start_time and print_increment, numbers such as 0.30000000000000004 and 5e-324: each
    format, and each format converted again, builds the model the XML builds, number for
    number (a marker given by its axes, which a dataset writes as REULER, to rounding), and
    runs alike."""
    ref = _load(EVERY)
    out = tmp_path / "out"
    out.mkdir()
    firsts = []
    for ext in (".adm", ".py", ".xml"):
        first = out / f"first{ext}"
        convert(EVERY, first)
        firsts.append(first)
        assert model_differences(ref, _load(first), rounded=ext != ".xml") == [], ext
    for first in firsts:
        for ext in (".adm", ".py", ".xml"):
            again = tmp_path / f"{first.stem}_{first.suffix[1:]}{ext}"
            convert(first, again)
            rounded = (first.suffix, ext) != (".xml", ".xml")
            assert model_differences(ref, _load(again), rounded=rounded) == [], again.name
    res = ref.run(progress=False)
    # the assembly's row at t = 0, 5 steps, then 100 (print_increment is kept, not used)
    assert res.success and len(res.t) == 1 + 5 + 100, res.message
    for first in firsts:
        model = _load(first)
        _runs_alike(model, model.run(progress=False), ref, res)


# every_attribute.xml gives print_increment, which draws its DeckWarning
@pytest.mark.filterwarnings("ignore::pysolver.errors.DeckWarning")
def test_the_dataset_holds_adams_statements_and_pysolver_extensions(tmp_path):
    """What the .adm says: exact digits, part-relative placement as written (ZP/XP where they
    give the axes exactly, else REULER), pysolver's statements and keywords, the commands in
    the .acf."""
    convert(EVERY, tmp_path / "every.adm")
    text = (tmp_path / "every.adm").read_text()
    for line in ("MARKER/2, PART = 1, QP = 0.30000000000000004, 5e-324, 1e+300",
                 "MARKER/21, PART = 2, QP = 0.0, 2.0, 0.0, ZP = 1.0, 2.0, 0.0, XP = 0.0, 3.0, 0.0",
                 ", REULER = 2.498091544796509, 0.9272952180016122, -1.5707963267948968",
                 "VTORQUE/1, I = 20, ACTIONONLY, RM = 5, TY = 1e-4*SIN(TIME)\\, TZ = -0.001*WZ(20)\\",
                 "JOINT/1, FREE, I = 20, J = 1, VIRTUAL",
                 "SENSOR_EVALUATE/7, FUNCTION = DY(30)\\",
                 ", CNAMES = height, \"\", \"1e5\"",
                 ", FUNCTION = USER(30, -1)\\, ROUTINE = floor, INTERPRETER = PYTHON",
                 "GRAPHICS/1, TYPE = Cylinder, CENTER_MARKER_ID = 20, RADIUS = 1.50"):
        assert line in text.splitlines(), line
    assert max(len(ln) for ln in text.splitlines() if not ln.startswith("!")) <= 80
    assert (tmp_path / "every.acf").read_text().splitlines() == [
        "every", "every", "SIMULATE/INITIAL_CONDITIONS",
        "SIMULATE/DYNAMICS, START = 0.0, END = 0.1, STEPS = 5",
        "SIMULATE/DYNAMICS, DURATION = 0.1, PRINT_INCREMENT = 2", "STOP"]


RM_OTHER = TEST_DECKS / "forms" / "rm_other_body.xml"


def _marker_statements(text):
    """{id: the statement on one line} of a dataset's MARKER statements."""
    out, last = {}, None
    for line in text.splitlines():
        if line.startswith("MARKER/"):
            last = int(line.split(",")[0][len("MARKER/"):])
            out[last] = line
        elif line.startswith(",") and last is not None:
            out[last] += line
        else:
            last = None
    return out


def test_a_marker_placed_on_another_bodys_marker_is_written_in_its_parts_frame(tmp_path):
    """convert wrote MARKER/21, PART = 2, RM = 2 with marker 2 on PART/1 (trial 43, item 2),
    which Adams' RM cannot name (a marker of the same part). An rm_id on another body is
    written without RM, at the marker's global place (the same doubles) with its global
    axes: as the one marker of its rm_id chain that turns it gives them (REULER, YPR, EP:
    the same axes), else by ZP/XP where they give the axes exactly, else by REULER to
    rounding; an rm_id on the same body stays RM. The .adm
    and the class script, and each converted back to XML, build the deck's model (places
    number for number, axes to rounding: exactly where one marker turns it) and run alike."""
    ref = _load(RM_OTHER)
    convert(RM_OTHER, tmp_path / "rm.adm")
    markers = _marker_statements((tmp_path / "rm.adm").read_text())
    part = {mid: st.split(", ")[1] for mid, st in markers.items()}
    rms = {mid: int(st.rpartition("RM = ")[2]) for mid, st in markers.items() if "RM" in st}
    assert rms == {20: 21} and part[20] == part[21] == "PART = 2"
    assert [markers[mid] for mid in (21, 20, 22, 25, 26, 30)] == [
        "MARKER/21, PART = 2, QP = 0.1, 0.0, 0.0, REULER = 0.0, 0.3, 0.0",
        "MARKER/20, PART = 2, QP = 0.0, 0.05464441137043903, -0.3309289777368827, RM = 21",
        "MARKER/22, PART = 2, QP = 0.270810328912638, 0.3144967706285145, "
        "-0.05960079923851836, YPR = 0.4, -0.2, 0.1",
        "MARKER/25, PART = 2, QP = 0.5, 0.0, -0.4",
        "MARKER/26, PART = 2, QP = 0.0, 0.0, -0.1, EP = 0.9, 0.1, -0.3, 0.2",
        "MARKER/30, POINT_MASS = 3, QP = 0.2487153924875332, 0.3159941395949384, "
        "-0.15711783195869997, YPR = 0.4, -0.2, 0.1"]
    # turned by two markers (23): the 3-1-3 angles of the axes; by nine numbers (24): the
    # points on its axes, which give them exactly
    assert ", REULER = " in markers[23] and ", ZP = " in markers[24] and ", XP = " in markers[24]
    convert(RM_OTHER, tmp_path / "rm.py")
    script = (tmp_path / "rm.py").read_text()
    assert "rm=" in script and script.count("rm=") == 1 and "rm=marker21" in script
    convert(tmp_path / "rm.adm", tmp_path / "rm_adm.xml")
    convert(tmp_path / "rm.py", tmp_path / "rm_py.xml")
    res = ref.run(progress=False)
    assert res.success, res.message
    for name in ("rm.adm", "rm.py", "rm_adm.xml", "rm_py.xml"):
        model = _load(tmp_path / name)
        assert model_differences(ref, model, rounded=True) == [], name
        for mid in (1, 2, 3, 4, 20, 21, 22, 24, 25, 26, 30):
            assert np.array_equal(model.markers[mid].rot, ref.markers[mid].rot), (name, mid)
        _runs_alike(model, model.run(progress=False), ref, res)


def test_the_command_line_writes_the_format_the_extension_names(tmp_path, capsys):
    """-o x.adm writes x.adm and x.acf, -o x.py a script of msolve classes, -o x.xml XML;
    any other extension is one line naming the formats (exit 2)."""
    deck = DECKS / "joints" / "slider_crank.xml"
    for name in ("sc.adm", "sc.py", "sc.xml"):
        assert main(["convert", str(deck), "-o", str(tmp_path / name)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == f"wrote {tmp_path / 'sc.adm'}, {tmp_path / 'sc.acf'}"
    assert lines[1:] == [f"wrote {tmp_path / 'sc.py'}", f"wrote {tmp_path / 'sc.xml'}"]
    ref = _load(deck)
    for name in ("sc.adm", "sc.acf", "sc.py", "sc.xml"):
        assert model_differences(ref, _load(tmp_path / name)) == [], name
    assert main(["convert", str(deck), "-o", str(tmp_path / "sc.txt")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("pysolver: error: ")
    assert "unknown output format '.txt': pysolver convert writes MotionSolve XML (.xml), " \
        "an Adams dataset with its command file (.adm), a script of msolve classes (.py)" in err
    assert not (tmp_path / "sc.txt").exists()


def test_convert_makes_the_output_folder(tmp_path, capsys, monkeypatch):
    """-o newdir/sc.xml failed with 'No such file or directory' while run -o makes its folder
    (trial 43, item 4): the folders are made, an .adm's .acf beside it; a path through a file
    is one line naming it (exit 2)."""
    deck = DECKS / "joints" / "slider_crank.xml"
    monkeypatch.chdir(tmp_path)
    assert main(["convert", str(deck), "-o", "newdir/sc.xml"]) == 0
    assert main(["convert", str(deck), "-o", "a/b/sc.adm"]) == 0
    assert capsys.readouterr().out.splitlines() == [
        "wrote newdir/sc.xml", "wrote a/b/sc.adm, a/b/sc.acf"]
    ref = _load(deck)
    for name in ("newdir/sc.xml", "a/b/sc.adm"):
        assert model_differences(ref, _load(tmp_path / name)) == [], name
    (tmp_path / "plain").write_text("")
    assert main(["convert", str(deck), "-o", "plain/sc.xml"]) == 2
    assert capsys.readouterr().err == "pysolver: error: plain: exists and is not a folder\n"
    assert main(["convert", str(deck), "-o", "plain/sub/sc.xml"]) == 2
    assert capsys.readouterr().err == "pysolver: error: plain/sub: Not a directory\n"


def test_convert_leaves_nothing_new_when_a_file_cannot_be_written(tmp_path, capsys,
                                                                  monkeypatch):
    """Trial 44, defect 5: -o cv2/y.adm with cv2/y.acf a folder wrote y.adm and then failed.
    Now both are written or neither: no y.adm, no temporary file, an older y.adm kept as it
    was, and a folder made for the output removed again."""
    deck = DECKS / "joints" / "slider_crank.xml"
    monkeypatch.chdir(tmp_path)
    (tmp_path / "cv2" / "y.acf").mkdir(parents=True)
    assert main(["convert", str(deck), "-o", "cv2/y.adm"]) == 2
    assert capsys.readouterr().err == "pysolver: error: cv2/y.acf: Is a directory\n"
    assert sorted(p.name for p in (tmp_path / "cv2").iterdir()) == ["y.acf"]
    (tmp_path / "cv2" / "y.adm").write_text("older")
    assert main(["convert", str(deck), "-o", "cv2/y.adm"]) == 2
    assert sorted(p.name for p in (tmp_path / "cv2").iterdir()) == ["y.acf", "y.adm"]
    assert (tmp_path / "cv2" / "y.adm").read_text() == "older"
    (tmp_path / "cv2" / "z.adm").mkdir()
    assert main(["convert", str(deck), "-o", "cv2/z.adm"]) == 2
    assert capsys.readouterr().err.splitlines()[-1] == \
        "pysolver: error: cv2/z.adm: Is a directory"
    assert not (tmp_path / "cv2" / "z.acf").exists()

    def refuse(src, dst):                       # the second rename fails
        if dst.endswith(".acf"):
            raise PermissionError(13, "Permission denied", dst)
        real(src, dst)
    real = os.replace
    monkeypatch.setattr(os, "replace", refuse)
    assert main(["convert", str(deck), "-o", "new/deep/w.adm"]) == 2
    assert capsys.readouterr().err == "pysolver: error: new/deep/w.acf: Permission denied\n"
    assert not (tmp_path / "new").exists()


def test_a_deck_without_commands_has_no_command_file(tmp_path):
    """No .acf beside the dataset (it loads with the default command, as the XML); one left
    from before would give it commands, so it is written again with none."""
    deck = tmp_path / "bare.xml"
    deck.write_text((DECKS / "joints" / "pendulum_revolute.xml").read_text().split(
        "</Model>")[0] + "</Model></MotionSolve>\n")
    convert(deck, tmp_path / "bare.adm")
    assert not (tmp_path / "bare.acf").exists()
    shutil.copy(DECKS / "forms" / "adams" / "joints" / "pendulum_revolute.acf",
                tmp_path / "bare.acf")
    assert convert(deck, tmp_path / "bare.adm") == [str(tmp_path / "bare.adm"),
                                                   str(tmp_path / "bare.acf")]
    assert (tmp_path / "bare.acf").read_text() == "bare\nbare\nSTOP\n"
    assert model_differences(_load(deck), _load(tmp_path / "bare.adm")) == []


def test_what_a_file_cannot_hold_is_a_deck_error(tmp_path):
    """A routine given as a Python function (name it in a script), a label with both kinds
    of quote: a DeckError naming the deck, the line and the element."""
    deck = tmp_path / "fn.py"
    deck.write_text("def var(id, time, par, npar, dflag, iflag):\n    return time\n\n"
                    "PART(1, GROUND=True)\nMARKER(1, PART=1)\nMARKER(2, PART=2)\n"
                    "PART(2, MASS=1, CM=2, IP=[1, 1, 1])\nVARIABLE(1, ROUTINE=var)\n")
    for ext in (".adm", ".py", ".xml"):
        with pytest.raises(DeckError, match="a routine given as a Python function cannot be "
                                            "written") as err:
            convert(deck, tmp_path / f"fn{ext}")
        assert (err.value.file, err.value.line) == (str(deck), 8)
    deck = tmp_path / "quotes.xml"
    deck.write_text('<MotionSolve><Model><Body_Rigid id="1" isground="TRUE" '
                    'label="it&apos;s &quot;it&quot;"/></Model></MotionSolve>')
    with pytest.raises(DeckError, match="cannot be written to a dataset's adams_view_name") \
            as err:
        convert(deck, tmp_path / "quotes.adm")
    assert (err.value.file, err.value.line, err.value.element) == (str(deck), 1, "PART")


SPIN = TEST_DECKS / "spin"
#: turned_cm's spin in ground at t = 0: the XML's w_ic about the global axes; Adams' and
#: msolve's WX, WZ along the CM marker's (its y is global z, its z global -y).
GLOBAL, ALONG_CM = [0.3, 0.0, 1.0], [0.3, -1.0, 0.0]
SPIN_FORMS = {"turned_cm.xml": GLOBAL, "turned_cm.adm": ALONG_CM,
              "turned_cm_statements.py": ALONG_CM, "turned_cm_classes.py": ALONG_CM}


@pytest.mark.parametrize("name", list(SPIN_FORMS))
def test_each_form_reads_a_spin_in_the_axes_its_documentation_gives(name):
    """A CM marker turned 90 degrees about x, a spin of 0.3 and 1 about x and z: MotionSolve's
    w_ic_* are about the global axes, Adams' PART WX.. and msolve's about the CM marker's
    (WX(20), WY(20), WZ(20) at t = 0; the body-axis channels are the same vector)."""
    res = _load(SPIN / name).run(progress=False)
    assert res.success, res.message
    w = np.array(SPIN_FORMS[name])
    np.testing.assert_allclose(res.request(1)[0, :3], w, atol=1e-15)
    np.testing.assert_allclose(res.request(1)[0, 3:6], [w[0], w[2], -w[1]], atol=1e-15)


def test_wm_id_on_the_cm_marker_reads_xml_w_ic_as_adams_reads_wx():
    """wm_id = the centre-of-mass marker: the XML deck builds the Adams deck's model."""
    text = (SPIN / "turned_cm.xml").read_text().replace('w_ic_z="1"', 'w_ic_z="1" wm_id="20"')
    assert model_differences(_load(SPIN / "turned_cm.adm"), pysolver.loads(text)) == []


@pytest.mark.parametrize("name", list(SPIN_FORMS))
def test_converting_a_spin_keeps_it_in_every_format(name, tmp_path):
    """Each form converted to XML, .adm and msolve classes, and each of those converted
    again, builds its model number for number and runs alike (1e-12): an XML spin about the
    global axes goes to the .adm as the body's own components, Adams' WX.. go to the XML with
    wm_id = the CM marker."""
    ref = _load(SPIN / name)
    res = ref.run(progress=False)
    texts = {}
    for ext in (".xml", ".adm", ".py"):
        first = tmp_path / f"first{ext}"
        convert(SPIN / name, first)
        texts[ext] = first.read_text()
        for again_ext in (".xml", ".adm", ".py"):
            again = tmp_path / f"again_{ext[1:]}{again_ext}"
            convert(first, again)
            assert model_differences(ref, _load(again)) == [], again.name
        assert model_differences(ref, _load(first)) == [], ext
        _same_results(_load(first).run(progress=False), res)
    part = [ln for ln in texts[".adm"].splitlines() if ln.startswith(("PART/2", ", W"))]
    if name.endswith(".xml"):
        assert "WX = 0.3, WY = 1.0, WZ = 0.0" in " ".join(part)
        assert "wm_id" not in texts[".xml"]
    else:
        body = [ln for ln in texts[".xml"].splitlines() if '<Body_Rigid id="2"' in ln][0]
        assert 'w_ic_x="0.3" w_ic_z="1"' in body and 'wm_id="20"' in body
        assert "WM" not in " ".join(part)


#: Each spin form's text and how a spin of 2 about y is written in it by hand.
SPIN_EDITS = {"turned_cm.xml": ('w_ic_x="0.3"', 'w_ic_x="0.3" w_ic_y="2.0"'),
              "turned_cm.adm": ("WX = 0.3, WZ = 1", "WX = 0.3, WY = 2.0, WZ = 1"),
              "turned_cm_statements.py": ("WX=0.3, WZ=1", "WX=0.3, WY=2.0, WZ=1"),
              "turned_cm_classes.py": ("wx=0.3, wz=1", "wx=0.3, wy=2.0, wz=1")}


@pytest.mark.parametrize("name", list(SPIN_FORMS))
def test_a_sweep_sets_w_ic_as_the_deck_gives_it(name, tmp_path):
    """Body_Rigid/2/w_ic_* of a sweep are the deck's own numbers, in the axes the form reads
    them in (the XML's about the global axes, Adams' and msolve's WX.. along the CM marker's):
    the deck's numbers come back as the values, a case is the deck edited by hand bit for bit
    (the spin in ground is the form's), and the next run is the deck's again, exactly."""
    model = _load(SPIN / name)
    params = model.compile().parameters
    assert [params._get(f"Body_Rigid/2/w_ic_{c}") for c in "xyz"] == [0.3, 0.0, 1.0]
    plain = model.run(progress=False)
    case = model.run(progress=False, params={"Body_Rigid/2/w_ic_y": 2.0})
    old, new = SPIN_EDITS[name]
    edited = tmp_path / name
    edited.write_text((SPIN / name).read_text().replace(old, new))
    if name.endswith(".adm"):
        (tmp_path / "turned_cm.acf").write_text((SPIN / "turned_cm.acf").read_text())
    by_hand = _load(edited).run(progress=False)
    assert np.array_equal(case.y, by_hand.y)
    assert np.array_equal(case.request(1), by_hand.request(1))
    # about global y in the XML; along the CM marker's y, which is global z, in the others
    w = np.array(SPIN_FORMS[name]) + ([0.0, 2.0, 0.0] if name.endswith(".xml") else
                                      [0.0, 0.0, 2.0])
    np.testing.assert_allclose(case.request(1)[0, :3], w, atol=1e-15)
    assert np.array_equal(model.run(progress=False).request(1), plain.request(1))
