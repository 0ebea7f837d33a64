"""Make the pictures of docs/gallery.md: for each example deck its figure (``res.plot``) and a
frame of its 3-D animation rendered by headless Chromium (``scene.html`` at a chosen time).

Run from the checkout root: ``python docs/gallery/make.py`` (needs matplotlib, Pillow and
Chromium: Debian's ``chromium`` or the binary ``PYSOLVER_CHROMIUM`` names). Writes
``docs/gallery/<deck>_plot.png`` and ``docs/gallery/<deck>_scene.png``.
"""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(ROOT))

import pysolver  # noqa: E402 - the checkout's pysolver, put on the path just above

#: deck (under decks/) -> the time its animation frame shows
DECKS = {
    "particle_between_lines.xml": 1.5,
    "catenary_bead.xml": 1.0,
    "spinning_top.xml": 0.5,
    "sensor_halt_acceleration.xml": None,       # the last row: where the sensor halted it
    "loadcontrol_indenter.xml": 2.5,
    "static_pendulum.xml": None,
    "joints/slider_crank.xml": 0.3,
    "joints/iftomm_a05_flyball.xml": 2.0,
}

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--proxy-server=http://127.0.0.1:9", "--proxy-bypass-list=<-loopback>",
         "--window-size=800,520", "--virtual-time-budget=5000"]


def chromium():
    """The Chromium binary, or None."""
    return os.environ.get("PYSOLVER_CHROMIUM") or next(
        (shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")
         if shutil.which(n)), None)


def main():
    browser = chromium()
    for name, t in DECKS.items():
        stem = pathlib.Path(name).stem
        model = pysolver.load(ROOT / "decks" / name)
        res = model.run(progress=False)
        res.plot(HERE / f"{stem}_plot.png")
        if browser is None:
            print(f"{name}: no Chromium, no animation frame")
            continue
        with tempfile.TemporaryDirectory() as tmp:
            page = pathlib.Path(tmp) / "scene.html"
            res.animate(model).save(page)
            when = res.t[-1] if t is None else t
            subprocess.run([browser, *FLAGS, f"--user-data-dir={tmp}/profile",
                            f"--screenshot={HERE / f'{stem}_scene.png'}",
                            f"{page.as_uri()}#t={when!r}"], capture_output=True, timeout=180,
                           check=True)
        print(f"{name}: {res.message} ({len(res.t)} rows)")


if __name__ == "__main__":
    main()
