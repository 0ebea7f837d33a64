"""The animation page: one HTML file with three.js, the scene's data and the viewer's
script inlined (no network when it is viewed)."""
import json
import pathlib
import re

from .._version import __version__

HERE = pathlib.Path(__file__).resolve().parent
#: The three.js release vendored in vendor/three.min.js (vendor/fetch.sh rebuilds it).
THREE_VERSION = "0.187.0"


def _script(text):
    """Text safe inside a <script> element (the parser ends it at the first "</script")."""
    return re.sub(r"</(script)", r"<\\/\1", text, flags=re.I)


def html(data):
    """The page of a scene's data (:meth:`pysolver.viewer.scene.Scene.data`) as a string."""
    template = (HERE / "page.html").read_text(encoding="utf-8")
    values = {
        "VERSION": __version__, "THREE_VERSION": THREE_VERSION,
        "TITLE": data["title"].replace("&", "&amp;").replace("<", "&lt;"),
        "THREE": _script((HERE / "vendor" / "three.min.js").read_text(encoding="utf-8")),
        "SCENE": _script(json.dumps(data, separators=(",", ":"), allow_nan=False)),
        "VIEWER": _script((HERE / "viewer.js").read_text(encoding="utf-8")),
    }
    return re.sub(r"@([A-Z_]+)@", lambda m: values[m.group(1)], template)
