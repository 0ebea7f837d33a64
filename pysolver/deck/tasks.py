"""Custom tasks: LoadControl (seed 002), checked at load.

The task drives its body along one global axis with a velocity motion whose expression is the
controller's output (the tree ``("ctrl", k)``: a value the controller sets at each update,
constant in between). The motion is kept in ``Model.motions`` under the id ``-id``, so its
reaction, the recorded load, is ``res.motion(-id)``.
"""
import re

import numpy as np

from ..errors import ExpressionError
from ..model import LoadControl, Motion
from . import expr as ex
from .motions import clashes

_T = re.compile(r"(?<![A-Za-z0-9_])t(?![A-Za-z0-9_])")


def add_loadcontrol(model, ctx, a):
    """Validate one LoadControl task and add it, with its drive, to the model."""
    lid = a["id"] if a["id"] is not None else len(model.controls) + 1
    ctx.id = lid
    if lid in model.controls:
        raise ctx.error(f"duplicate LoadControl id {lid}", "id")
    body = model.bodies.get(a["material"])
    if body is None or body.kind == "ground":
        raise ctx.error(f"material {a['material']} is not a moving Body_Rigid or Body_Point",
                        "material")
    if not 0.0 < a["smooth"] < 1.0:
        raise ctx.error(f"got {a['smooth']:g}; expected 0 < smooth < 1", "smooth")
    text = a["load_function"]
    try:
        tree = ex.parse(_T.sub("TIME", text))
    except ExpressionError as err:
        raise ctx.error(f"bad Load_Function {text!r}: {err}", "load_function") from None
    axis = int(a["direction"]) - 1
    direction = "XYZ"[axis]
    marker = _cg_marker(model, body)
    if marker is None:
        raise ctx.error(f"body {body.id} has no marker at its origin to drive", "material")
    other = clashes(model, body.id, 0, direction, None)
    if other is not None:
        raise ctx.error(f"Motion_Marker {other} already drives body {body.id} along "
                        f"{direction}; it would fight the controller", "material")
    k = len(model.controls)
    motion = Motion(-lid, marker, 0, direction, "V", ("ctrl", k),
                    f"LoadControl {lid} velocity")
    model.motions[-lid] = motion
    model.controls[lid] = LoadControl(
        lid, body.id, axis, a["velocity"], a["maxvelocity"], tree, text, a["kp"], a["ki"],
        a["smooth"], a["updatetime"], a["median_window"], -lid, a["load"], a["label"])
    model._where[("loadcontrol", lid)] = ctx


def _cg_marker(model, body):
    """A marker on the body at its origin with its axes (the cg marker), else any at its origin."""
    found = None
    for m in sorted(model.markers.values(), key=lambda m: m.id):
        if m.body == body.id and np.allclose(m.pos, body.pos, rtol=0, atol=1e-12):
            if np.allclose(m.rot, body.rot, rtol=0, atol=1e-12):
                return m.id
            found = found or m.id
    return found
