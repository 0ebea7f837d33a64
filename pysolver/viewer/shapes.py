"""What the 3-D view draws for each element, as plain dicts the page's script builds meshes
from (docs/animation.md lists them).

Two kinds of item:

- a *shape* is fixed in a marker's frame (``marker``) and moves with its body: ``cylinder``
  (radii r0 at z0 and r1 at z1 along the marker's z), ``box`` (centre c, size s), ``sphere``
  (centre c, radius r, scale for an ellipsoid), ``arc`` (radius r from angle a0 to a1 in the
  xy plane), ``square`` (side s in the xy plane), ``helix`` (radius r from z0 to z1, turns),
  ``spiral`` (radius r0 to r1 in the xy plane, turns), ``axis`` (a line from z0 to z1);
- a *link* joins the origins of markers on different bodies and is rebuilt every frame:
  ``coil`` (radius r, turns), ``line`` (dashed or not), ``polyline`` (through ``markers``).

Sizes are in model length units; ``g`` is the glyph size the scene's extent sets.
"""
import math
import re

import numpy as np

from ..catalogue import NAMES

#: Colours (CSS hex) by role.
JOINT, DRIVEN, SPRING, FORCE, PLANE = "#d9822b", "#8e44ad", "#2a9d55", "#c0392b", "#4a78b5"
GRAPHIC = "#8aa1b5"


class Skip(Exception):
    """An element the view cannot draw; its message says why (shown as a note)."""


def _number(attrs, *names, default=None):
    for name in names:
        if attrs.get(name) not in (None, ""):
            try:
                return float(attrs[name])
            except ValueError:
                raise Skip(f"{name}={attrs[name]!r} is not a number") from None
    if default is None:
        raise Skip(f"no {names[0]}")
    return default


def _marker(attrs, markers, *names):
    for name in names:
        if attrs.get(name) not in (None, ""):
            try:
                mid = int(float(attrs[name]))
            except ValueError:
                raise Skip(f"{name}={attrs[name]!r} is not a marker id") from None
            if mid not in markers:
                raise Skip(f"{name}: marker {mid} does not exist")
            return mid
    raise Skip(f"no {names[0]}")


def _color(attrs, default=GRAPHIC):
    """A deck's ``color="r:g:b"`` (0-255) as CSS hex, else the default."""
    parts = re.split(r"[:,\s]+", str(attrs.get("color", "")).strip())
    if len(parts) == 3:
        try:
            rgb = [min(255, max(0, int(float(p)))) for p in parts]
            return "#{:02x}{:02x}{:02x}".format(*rgb)
        except ValueError:
            pass
    return default


def _true(value):
    return str(value).strip().upper() in ("TRUE", "YES", "1")


# Post_Graphic (MotionSolve XML names first, then Adams GRAPHICS keywords) ------------------
CENTER = ("center_marker_id", "cm", "cm_marker_id")
CORNER = ("corner_marker_id", "corner")


def graphic(gr, markers, poses, g):
    """The shapes and links of one Post_Graphic; Skip when it cannot be drawn."""
    a = {k.lower(): v for k, v in gr.attrs.items()}
    kind = re.sub(r"[\s_]", "", gr.type).upper()
    base = {"color": _color(a), "label": f"Post_Graphic {gr.id}" + (f" {gr.label}"
                                                                    if gr.label else "")}
    if kind == "CYLINDER":
        r, length = _number(a, "radius"), _number(a, "length")
        return [dict(base, kind="cylinder", marker=_marker(a, markers, *CENTER), r0=r, r1=r,
                     z0=0.0, z1=length, open=str(a.get("ends_type", "")).upper() == "OPEN")]
    if kind == "FRUSTUM":
        return [dict(base, kind="cylinder", marker=_marker(a, markers, *CENTER),
                     r0=_number(a, "bottom_radius", "bottom", "radius_bottom"),
                     r1=_number(a, "top_radius", "top", "radius_top"),
                     z0=0.0, z1=_number(a, "length"), open=False)]
    if kind in ("BOXDEFINEDFROMCORNER", "BOXDEFINEDFROMCENTER", "BOX"):
        size = [_number(a, f"length_{x}", x) for x in "xyz"]
        corner = kind != "BOXDEFINEDFROMCENTER"
        mid = _marker(a, markers, *(CORNER if corner else CENTER))
        c = [s / 2 if corner else 0.0 for s in size]
        return [dict(base, kind="box", marker=mid, c=c, s=[abs(s) for s in size])]
    if kind in ("SPHERE", "ELLIPSOID"):
        if kind == "SPHERE":
            r, scale = _number(a, "radius"), [1.0, 1.0, 1.0]
        else:           # xscale.. are the diameters along the marker's axes
            d = [_number(a, f"{x}scale", f"{x}_scale") for x in "xyz"]
            if min(d) <= 0:
                raise Skip(f"its diameters must be > 0, got {d}")
            r, scale = max(d) / 2, [v / max(d) for v in d]
        return [dict(base, kind="sphere", marker=_marker(a, markers, *CENTER), c=[0, 0, 0],
                     r=r, scale=scale)]
    if kind.startswith(("CIRCLE", "ARC")):
        mid = _marker(a, markers, *CENTER)
        if any(a.get(k) not in (None, "") for k in ("radius", "r")):
            r = _number(a, "radius", "r")
        else:           # the distance to a reference marker
            ref = _marker(a, markers, "ref_marker_id", "rm", "rm_marker_id")
            r = float(np.linalg.norm(poses.marker_position(ref)[0]
                                     - poses.marker_position(mid)[0]))
        end = 2 * math.pi if kind.startswith("CIRCLE") else \
            _number(a, "range_angle", "rangle", "angle")
        return [dict(base, kind="arc", marker=mid, r=r, a0=0.0, a1=end)]
    if kind == "OUTLINE":
        text = next((a[k] for k in ("outline", "marker_id_list", "marker_ids", "markers")
                     if a.get(k) not in (None, "")), None)
        if text is None:
            raise Skip("no list of markers (marker_id_list=, or Adams OUTLINE=)")
        ids = [_marker({"outline": part}, markers, "outline")
               for part in re.split(r"[,\s]+", str(text).strip()) if part]
        if len(ids) < 2:
            raise Skip("an outline joins two markers or more")
        return [dict(base, kind="polyline", markers=ids)]
    if kind == "SPDP":
        i = _marker(a, markers, "i_marker_id", "i")
        j = _marker(a, markers, "j_marker_id", "j")
        return [dict(base, kind="coil", markers=[i, j], r=_number(a, "da", "diameter") / 2,
                     turns=_number(a, "coils", "num_coils", default=8.0))]
    if kind == "POINT":
        return [dict(base, kind="sphere", marker=_marker(a, markers, "marker_id", *CENTER),
                     c=[0, 0, 0], r=0.3 * g, scale=[1, 1, 1])]
    raise Skip(f"type {gr.type} is not drawn (meshes, CAD files, curves and surfaces are not "
               f"read)")


# joints ----------------------------------------------------------------------------------
def travel(poses, i, j):
    """Range (min, max) of DZ(I, J, J) over the rows: where a slider has been along zJ."""
    d = np.einsum("ni,ni->n", poses.marker_position(i) - poses.marker_position(j),
                  poses.marker_axes(j)[:, :, 2])
    d = d[np.isfinite(d)]
    return (float(d.min()), float(d.max())) if len(d) else (0.0, 0.0)


def joint(jo, poses, g, driven=False):
    """The shapes of one Constraint_Joint (on I's body at I, on J's body at J)."""
    color = DRIVEN if driven else JOINT
    base = {"color": color, "label": f"Constraint_Joint {jo.id} {jo.type}"
            + (f" {jo.label}" if jo.label else "")}
    i, j, t = jo.i, jo.j, jo.type

    def rail(r):
        lo, hi = travel(poses, i, j)
        return dict(base, kind="cylinder", marker=j, r0=r, r1=r, z0=lo - 2 * g, z1=hi + 2 * g,
                    open=False)

    pin = dict(base, kind="cylinder", marker=j, r0=0.45 * g, r1=0.45 * g, z0=-1.5 * g,
               z1=1.5 * g, open=False)
    if t == "REVOLUTE":
        return [pin]
    if t in ("SPHERICAL", "ATPOINT"):
        return [dict(base, kind="sphere", marker=i, c=[0, 0, 0], r=0.8 * g, scale=[1, 1, 1])]
    if t == "FIXED":
        return [dict(base, kind="box", marker=i, c=[0, 0, 0], s=[1.2 * g] * 3)]
    if t == "TRANSLATIONAL":
        return [rail(0.25 * g), dict(base, kind="box", marker=i, c=[0, 0, 0],
                                     s=[1.4 * g, 1.4 * g, 2.2 * g])]
    if t == "CYLINDRICAL":
        return [rail(0.3 * g), dict(base, kind="cylinder", marker=i, r0=0.7 * g, r1=0.7 * g,
                                    z0=-1.1 * g, z1=1.1 * g, open=True)]
    if t in ("UNIVERSAL", "HOOKE", "CONSTANT_VELOCITY"):
        return [dict(pin, r0=0.3 * g, r1=0.3 * g), dict(pin, marker=i, r0=0.3 * g, r1=0.3 * g)]
    if t in ("PLANAR", "INPLANE"):
        return [dict(base, kind="square", marker=j, s=4 * g),
                dict(base, kind="sphere", marker=i, c=[0, 0, 0], r=0.35 * g, scale=[1, 1, 1])]
    if t == "INLINE":
        lo, hi = travel(poses, i, j)
        return [dict(base, kind="axis", marker=j, z0=lo - 2 * g, z1=hi + 2 * g),
                dict(base, kind="sphere", marker=i, c=[0, 0, 0], r=0.35 * g, scale=[1, 1, 1])]
    if t in ("ORIENTATION", "PARALLEL_AXES", "PERPENDICULAR"):
        return [dict(base, kind="axis", marker=j, z0=0.0, z1=2.5 * g),
                dict(base, kind="axis", marker=i, z0=0.0, z1=2.5 * g)]
    if t == "SCREW":
        lo, hi = travel(poses, i, j)
        turns = (hi - lo + 4 * g) / (2 * math.pi * abs(jo.lead)) if jo.lead else 6.0
        return [rail(0.25 * g), dict(base, kind="helix", marker=j, r=0.45 * g, z0=lo - 2 * g,
                                     z1=hi + 2 * g, turns=min(turns, 200.0)),
                dict(base, kind="cylinder", marker=i, r0=0.8 * g, r1=0.8 * g, z0=-0.6 * g,
                     z1=0.6 * g, open=True)]
    if t == "RACK_PINION":
        r = abs(jo.lead) or g
        return [rail(0.25 * g), dict(base, kind="cylinder", marker=i, r0=r, r1=r, z0=-0.3 * g,
                                     z1=0.3 * g, open=False)]
    return []                   # FREE: nothing to hold


# forces ----------------------------------------------------------------------------------
def spring(sd, g):
    """A Force_SpringDamper: a coil from J to I, or a clock spring about zJ."""
    label = f"Force_SpringDamper {sd.id}" + (f" {sd.label}" if sd.label else "")
    if sd.type == "ROTATIONAL":
        return [dict(kind="spiral", marker=sd.j, r0=0.3 * g, r1=1.4 * g, turns=3.0,
                     color=SPRING, label=label),
                dict(kind="axis", marker=sd.i, z0=0.0, z1=1.6 * g, color=SPRING, label=label)]
    return [dict(kind="coil", markers=[sd.j, sd.i], r=0.7 * g, turns=10.0, color=SPRING,
                 label=label)]


def bushing(bu, g):
    label = f"Force_Bushing {bu.id}" + (f" {bu.label}" if bu.label else "")
    return [dict(kind="box", marker=bu.i, c=[0, 0, 0], s=[1.1 * g] * 3, color=SPRING,
                 label=label, opacity=0.6),
            dict(kind="line", markers=[bu.j, bu.i], dashed=False, color=SPRING, label=label)]


def field(el, g):
    """A Force_Field: drawn as a bushing is."""
    label = f"Force_Field {el.id}" + (f" {el.label}" if el.label else "")
    return [dict(item, label=label) for item in bushing(el, g)]


def beam(el, g):
    """A Force_Beam: a line from J to I (the beam's axis while it is straight)."""
    label = f"Force_Beam {el.id}" + (f" {el.label}" if el.label else "")
    return [dict(kind="line", markers=[el.j, el.i], dashed=False, color=SPRING, label=label)]


def scalar_force(sf):
    label = f"Force_Scalar_TwoBody {sf.id}" + (f" {sf.label}" if sf.label else "")
    return [dict(kind="line", markers=[sf.j, sf.i], dashed=True, color=FORCE, label=label)]


# penalties: an expression affine in one marker's global position is a plane ------------------
def affine(tree, model):
    """(c, marker id, a) with the expression = c + a . p(marker), or None when it is not
    (only numbers, named constants, + - * / by numbers and DX/DY/DZ of one marker
    relative to ground markers)."""
    node = tree[0]
    if node == "num":
        return tree[1], None, np.zeros(3)
    if node == "name":
        f = NAMES.get(tree[1].upper())
        return (f.py(), None, np.zeros(3)) if f is not None and f.py is not None else None
    if node == "neg":
        x = affine(tree[1], model)
        return None if x is None else (-x[0], x[1], -x[2])
    if node == "call" and tree[1].upper() in ("DX", "DY", "DZ"):
        return _displacement(tree[1].upper(), tree[2], model)
    if node != "bin":
        return None
    op, a, b = tree[1], affine(tree[2], model), affine(tree[3], model)
    if a is None or b is None:
        return None
    if op in "+-":
        if a[1] is not None and b[1] is not None and a[1] != b[1]:
            return None
        s = 1.0 if op == "+" else -1.0
        return a[0] + s * b[0], a[1] if a[1] is not None else b[1], a[2] + s * b[2]
    if op == "*" and (a[1] is None or b[1] is None):
        k, x = (a, b) if a[1] is None else (b, a)
        return k[0] * x[0], x[1], k[0] * x[2]
    if op == "/" and b[1] is None and b[0] != 0:
        return a[0] / b[0], a[1], a[2] / b[0]
    return None


def _displacement(name, args, model):
    ids = []
    for arg in args:
        if arg[0] != "num":
            return None
        ids.append(int(arg[1]))
    ids += [0] * (3 - len(ids))
    i, j, k = ids
    if i not in model.markers:
        return None
    origin, axes = np.zeros(3), np.eye(3)
    for mid, use in ((j, "origin"), (k, "axes")):
        if mid == 0:
            continue
        m = model.markers.get(mid)
        if m is None or model.bodies[m.body].kind != "ground":
            return None         # relative to a moving marker: not a plane fixed in space
        if use == "origin":
            origin = np.asarray(m.pos, float)
        else:
            axes = np.asarray(m.rot, float)
    a = axes[:, "XYZ".index(name[1])]
    return -float(a @ origin), i, a


def penalty_planes(penalties, model, poses, g):
    """The Force_Penalty elements whose expression is a plane in one marker's position: per
    plane (penalties on one plane drawn once), the patch of g = 0 under the markers' paths
    (projected onto it, 3 glyphs more each side, at least 12 glyphs across)."""
    planes = {}
    for pen in sorted(penalties, key=lambda p: p.id):
        got = affine(pen.expr, model) if pen.expr is not None else None
        if got is None or got[1] is None or not np.any(got[2]):
            continue
        c, mid, a = got
        n, d = a / np.linalg.norm(a), c / np.linalg.norm(a)      # the plane n . p + d = 0
        if n[np.flatnonzero(np.abs(n) > 1e-12)[0]] < 0:
            n, d = -n, -d
        key = tuple(np.round(n, 9)) + (round(d / g, 6),)
        plane = planes.setdefault(key, {"n": n, "d": d, "paths": [], "pens": []})
        plane["paths"].append(poses.marker_position(mid))
        plane["pens"].append(pen)
    return [_patch(pl["n"], pl["d"], np.concatenate(pl["paths"]), pl["pens"], g)
            for pl in planes.values()]


def _patch(n, d, path, pens, g):
    path = path[np.all(np.isfinite(path), axis=1)]
    if not len(path):
        path = np.zeros((1, 3)) - d * n
    on = path - (path @ n + d)[:, None] * n             # the paths projected onto the plane
    u = np.cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    pu, pv = on @ u, on @ v
    w, h = (max(x.max() - x.min() + 6 * g, 12 * g) for x in (pu, pv))
    centre = (on[0] - (pu[0] - (pu.min() + pu.max()) / 2) * u
              - (pv[0] - (pv.min() + pv.max()) / 2) * v)
    if len(pens) == 1:
        label = f"Force_Penalty {pens[0].id}" + (f" {pens[0].label}" if pens[0].label else "")
    else:
        ids = ", ".join(str(p.id) for p in pens[:3]) + (", ..." if len(pens) > 3 else "")
        label = f"Force_Penalty {ids} ({len(pens)} on one plane)"
    return dict(kind="plane", centre=centre.tolist(), u=u.tolist(), v=v.tolist(), w=w, h=h,
                color=PLANE, label=label)
