"""The animation page in a real browser: headless Chromium (Debian's package ``chromium``, or
the one PYSOLVER_CHROMIUM names) renders tests/decks/graphics.xml's page at two times, with
every network request sent to a dead proxy; the pictures are not blank and the pendulum's
links are where the run had them moving; a page's note list is its Animation.notes. Skipped
where there is no Chromium."""
import os
import re
import shutil
import subprocess

import numpy as np
import pytest

import pysolver

from helpers import ROOT

Image = pytest.importorskip("PIL.Image")

CHROMIUM = os.environ.get("PYSOLVER_CHROMIUM") or next(
    (shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome",
                               "google-chrome-stable") if shutil.which(n)), None)
pytestmark = pytest.mark.skipif(
    CHROMIUM is None, reason="no Chromium to render the page (Debian: apt-get install "
                             "chromium; or set PYSOLVER_CHROMIUM to a Chrome/Chromium binary)")

#: Software WebGL (SwiftShader through ANGLE) draws the page without a GPU.
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--proxy-server=http://127.0.0.1:9", "--proxy-bypass-list=<-loopback>",
         "--window-size=800,520", "--virtual-time-budget=5000"]
SIZE = (800, 520)


def _shot(page, fragment, tmp_path):
    png = tmp_path / f"shot_{fragment.replace('=', '_')}.png"
    profile = tmp_path / f"profile_{fragment.replace('=', '_')}"
    run = subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}",
                          f"--screenshot={png}", f"{page.as_uri()}#{fragment}"],
                         capture_output=True, text=True, timeout=180)
    assert png.exists(), f"Chromium wrote no screenshot (exit {run.returncode}): {run.stderr}"
    pixels = np.asarray(Image.open(png).convert("RGB")).astype(int)
    assert pixels.shape == (SIZE[1], SIZE[0], 3)
    return pixels[60:-50]           # the 3-D view without the text on top and the bar


def _where(pixels, rgb, tol=45):
    """Centroid (x, y) and count of the pixels within `tol` of colour `rgb` in each channel
    (the lit faces of a mesh of that colour)."""
    ys, xs = np.nonzero(np.all(np.abs(pixels - np.asarray(rgb)) <= tol, axis=2))
    return (xs.mean() if len(xs) else np.nan, ys.mean() if len(ys) else np.nan), len(xs)


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    model = pysolver.load(ROOT / "tests" / "decks" / "graphics.xml")
    res = model.run(progress=False)
    path = tmp_path_factory.mktemp("page") / "scene.html"
    res.animate().save(path)
    return path, res


def test_the_page_draws_the_scene_and_the_bodies_move(page, tmp_path):
    """At t = 0 and t = 0.6 s: the view is not blank (background-coloured at most 97 %), the
    red tip sphere and the blue link-1 cylinder are on screen, and both moved: the tip to
    the left by more than 100 px and down, as the run's tip went 1.2 m toward the pivot
    (-x, to the left in this view) and 0.4 m down."""
    path, res = page
    first, later = _shot(path, "t=0", tmp_path), _shot(path, "t=0.6", tmp_path)
    background = np.array([244, 246, 248])
    for pixels in (first, later):
        plain = np.all(np.abs(pixels - background) <= 3, axis=2).mean()
        assert plain < 0.97, f"{plain:.1%} of the view is background"
    (tip0, n0), (tip1, n1) = _where(first, (200, 60, 40)), _where(later, (200, 60, 40))
    (rod0, m0), (rod1, m1) = _where(first, (70, 110, 170)), _where(later, (70, 110, 170))
    assert min(n0, n1) > 300 and min(m0, m1) > 300, (n0, n1, m0, m1)
    tip = res.request(1)[:, :3]                     # the run's tip: in 1.2 m and down 0.4 m
    np.testing.assert_allclose(tip[60] - tip[0], [-1.2079, 0, -0.3899], atol=1e-4)
    assert tip1[0] - tip0[0] < -100 and tip1[1] - tip0[1] > 20    # left and down the screen
    assert np.hypot(rod1[0] - rod0[0], rod1[1] - rod0[1]) > 20


def test_a_frame_fragment_opens_the_same_picture_as_its_time(page, tmp_path):
    """#frame=60 is row 60, t = 0.6 s: the same pixels as #t=0.6."""
    path, res = page
    assert res.t[60] == pytest.approx(0.6)
    a, b = _shot(path, "frame=60", tmp_path), _shot(path, "t=0.6", tmp_path)
    assert np.abs(a - b).max() <= 2


def test_the_notebook_iframe_draws_the_scene(tmp_path):
    """Result.animate()'s _repr_html_ (an iframe with the page as its srcdoc) inside another
    page, as a notebook shows it: the frame draws the scene (it plays from its start, so the
    red tip and the blue link are somewhere on their paths)."""
    model = pysolver.load(ROOT / "tests" / "decks" / "graphics.xml")
    cell = tmp_path / "notebook.html"
    cell.write_text("<!DOCTYPE html><html><body style='margin:0'>"
                    + model.run(progress=False).animate()._repr_html_() + "</body></html>",
                    encoding="utf-8")
    pixels = _shot(cell, "", tmp_path)
    (_, n), (_, m) = _where(pixels, (200, 60, 40)), _where(pixels, (70, 110, 170))
    assert n > 300 and m > 300, (n, m)


def test_the_page_lists_the_notes_of_animation_notes(tmp_path):
    """The page's note list, read from the DOM Chromium built: the same entries as
    Animation.notes, the rows kept first (worded once, in Python; the page once worded its
    own, "every 2th", and Animation.notes lacked it)."""
    res = pysolver.load(ROOT / "decks" / "particle_between_lines.xml").run(progress=False)
    anim = res.animate(max_frames=100)
    path = tmp_path / "thinned.html"
    anim.save(path)
    run = subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={tmp_path / 'profile'}",
                          "--dump-dom", f"{path.as_uri()}#t=0"],
                         capture_output=True, text=True, timeout=180)
    got = re.search(r'<details id="notes"[^>]*><summary>(.*?)</summary><ul>(.*?)</ul>',
                    run.stdout, re.S)
    assert got, f"no note list in the page (exit {run.returncode}): {run.stderr[-2000:]}"
    assert got.group(1) == "1 note"
    assert re.findall(r"<li>(.*?)</li>", got.group(2)) == anim.notes == \
        ["showing 87 of 601 output rows (every 7th and the last)"]


FALL = """<?xml version="1.0"?>
<MotionSolve>
  <Model>
    <Units mass="KILOGRAM" length="MILLIMETER" time="{unit}" force="NEWTON"/>
    <Body_Rigid id="1" isground="TRUE"/>
    <Reference_Marker id="1" body_id="1"/>
    <Reference_Marker id="10" body_id="2" pos_y="3"/>
    <Body_Point id="2" cg_id="10" mass="1.0"/>
    <Force_Gravity grav_y="-1e-6"/>
  </Model>
  <Simulate analysis_type="Transient" end_time="{end}" print_interval="{step}"/>
</MotionSolve>
"""


def _speeds(tmp_path, unit, end):
    """The speed menu Chromium built for a fall that lasts `end` in time unit `unit`: the
    options' (value, text) and the selected one's text."""
    res = pysolver.loads(FALL.format(unit=unit, end=end, step=end / 20)).run(progress=False)
    path = tmp_path / f"{unit}.html"
    res.animate().save(path)
    run = subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={tmp_path / unit}",
                          "--dump-dom", f"{path.as_uri()}#t=0"],
                         capture_output=True, text=True, timeout=180)
    menu = re.search(r'<select id="speed"[^>]*>(.*?)</select>', run.stdout, re.S)
    assert menu, f"no speed menu in the page (exit {run.returncode}): {run.stderr[-2000:]}"
    options = re.findall(r'<option value="([^"]*)"( selected="")?>(.*?)</option>',
                         menu.group(1))
    return [(float(v), text) for v, _, text in options], [t for _, s, t in options if s]


SECOND_STEPS = ["0.01×", "0.02×", "0.05×", "0.1×", "0.2×", "0.5×", "real time", "2×", "5×",
                "10×", "20×", "50×"]


@pytest.mark.parametrize("unit, end, selected, value, texts", [
    ("SECOND", 2.0, "real time", 1.0, SECOND_STEPS),
    ("MILLISECOND", 2000.0, "real time", 1000.0, SECOND_STEPS),
    ("MINUTE", 2.0, "20×", 1 / 3, ["0.1×", "0.2×", "0.5×", "real time", "2×", "5×", "10×",
                                   "20×", "50×", "100×", "200×", "500×", "1000×", "2000×",
                                   "5000×"]),
])
def test_the_speed_menu_is_in_multiples_of_real_time(tmp_path, unit, end, selected, value,
                                                     texts):
    """Trial 44, defect 2: a 2 s run written in ms offered "200×" (0.2x real time) and no
    "real time"; an option's value is deck time units per wall-clock second."""
    options, chosen = _speeds(tmp_path, unit, end)
    assert [text for _, text in options] == texts
    assert chosen == [selected]
    assert dict((t, v) for v, t in options)[selected] == pytest.approx(value, rel=1e-12)
