"""Force_SpringDamper (Adams SPRINGDAMPER): a spring and damper between two markers, held as
the scalar force or torque of a Force_Scalar_TwoBody that the model keeps under the negative
id (-id) beside the deck's own, so that it runs, differentiates and is diagnosed like one.

- TRANSLATIONAL: F = -k (r - L) - c r' + F0 along the line from J to I (positive repels),
  r = DM(I, J), r' = VR(I, J), L = `length`, F0 = `preload`; F on I, -F on J.
- ROTATIONAL: T = -k (a - A) - c a' + T0 about zJ, a = AZ(I, J) tracked through every turn
  (a "turned" angle: csrc/elements/turn.c), a' = WZ(I, J, J), A = `length` read as the
  reference angle in radians (MotionSolve's XML has no angle attribute), T0 = `preload`;
  T zJ on I, -T zJ on J.

k, c, L and the preload are parameters of sweeps (``Force_SpringDamper/<id>/stiffness``, ...).
"""
import numpy as np

from ..records import ScalarForce, SpringDamper
from . import expr as ex

#: The attributes a sweep may change, in the order of the force law.
NUMBERS = ("stiffness", "damping", "length", "preload")


def add_springdamper(model, ctx, a):
    """Validate one Force_SpringDamper, add it and the scalar force that holds it."""
    ctx.id = sid = a["id"]
    for key in ("i_marker_id", "j_marker_id"):
        if a[key] not in model.markers:
            raise ctx.error(f"marker {a[key]} does not exist", key)
    i, j = a["i_marker_id"], a["j_marker_id"]
    if model.markers[i].body == model.markers[j].body:
        raise ctx.error(f"markers {i} and {j} are on one body: a spring between them does "
                        "nothing", "j_marker_id")
    rotational = a["type"] == "ROTATIONAL"
    for key, mid in (("i_marker_id", i), ("j_marker_id", j)):
        if rotational and model.bodies[model.markers[mid].body].kind == "point":
            raise ctx.error(f"a ROTATIONAL spring turns rigid bodies; marker {mid} is on point "
                            f"body {model.markers[mid].body}", key)
    if not rotational and a["length"] < 0:
        raise ctx.error(f"got {a['length']:g}; a free length is >= 0", "length")
    spring = SpringDamper(sid, a["type"], i, j, a["stiffness"], a["damping"], a["length"],
                          a["preload"], a["label"])
    model.springdampers[sid] = spring
    par = {k: ("param", f"Force_SpringDamper/{sid}/{k}", getattr(spring, k)) for k in NUMBERS}
    if rotational:
        x = ("turned", ex.call("AZ", i, j), ("sforce", -sid, 0))
        rate = ex.call("WZ", i, j, j)
        text = f"-k (AZ({i},{j}) - angle) - c WZ({i},{j},{j}) + preload, AZ through every turn"
    else:
        x, rate = ex.call("DM", i, j), ex.call("VR", i, j)
        text = f"-k (DM({i},{j}) - length) - c VR({i},{j}) + preload"
    law = ("bin", "+", ("bin", "-", ("neg", ("bin", "*", par["stiffness"],
                                              ("bin", "-", x, par["length"]))),
                        ("bin", "*", par["damping"], rate)), par["preload"])
    model.sforces[-sid] = ScalarForce(-sid, rotational, i, j, law, text, a["label"],
                                      turns=rotational)
    model._where[("sforce", -sid)] = ctx
    model._where[("springdamper", sid)] = ctx


def fixed_line(ctx, model, a):
    """A Force_Scalar_TwoBody acting along the line from J to I between markers that coincide
    for ever (one marker, or two of one body at one place) has no direction: a DeckError
    (docs/deck-language.md, "Coincident markers"; a spring-damper's markers are on two
    bodies)."""
    if a["type"] == "TORQUE" or a["is_action_only"]:
        return
    mi, mj = (model.markers[a[k]] for k in ("i_marker_id", "j_marker_id"))
    if mi.body == mj.body and np.array_equal(mi.pos, mj.pos):
        what = "are one marker" if mi.id == mj.id else f"coincide on body {mi.body}"
        raise ctx.error(f"markers I = {mi.id} and J = {mj.id} {what}, so DM is 0 for ever and "
                        "a translational force, which acts along the line from J to I, has "
                        "no direction (docs/deck-language.md, \"Coincident markers\")",
                        "j_marker_id")
