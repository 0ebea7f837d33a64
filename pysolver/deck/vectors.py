"""Vector forces and bushings: Force_Vector_TwoBody, Force_Vector_OneBody and Force_Bushing,
all held as one kernel element (csrc/elements/vforce.c): a force and a torque by their
components in a reference marker's axes, on I's body at I and, for two bodies, opposite on
the other body at the same point.

A Force_Bushing (Adams BUSHING) is kept under the negative id (-id) of the vector forces, its
six components in J's axes (../shared/reference/elements.md section 4.2):

    F = -[kx DX, ky DY, kz DZ] - [cx VX, cy VY, cz VZ] + [fx0, fy0, fz0]
    T = -[ktx AX, kty AY, ktz AZ] - [ctx WX, cty WY, ctz WZ] + [tx0, ty0, tz0]

with DX = DX(I, J, J), VX = VX(I, J, J, J) (I's velocity relative to J seen from J), AX..AZ =
AX(I, J).. (single-axis angles: the small-angle convention, one large angle at most; Adams'
bushing page calls them "projected, small-angle rotational displacements", so they are the
values in (-pi, pi], not the angles AX..AZ of an expression, which count every turn) and WX =
WX(I, J, J). The reaction on J's body at I's point is -F and -T, which is -F and
-T - d x F at J's origin. Its 18 numbers are sweep parameters (``Force_Bushing/<id>/kx``...).
"""
from ..records import Bushing, VectorForce
from . import expr as ex

#: A bushing's numbers: stiffness, damping, preload per component.
STIFF = ("kx", "ky", "kz", "ktx", "kty", "ktz")
DAMP = ("cx", "cy", "cz", "ctx", "cty", "ctz")
LOAD = ("preload_x", "preload_y", "preload_z", "preload_tx", "preload_ty", "preload_tz")
_ZERO = ("num", 0.0)


def _call(name, *ids):
    return ("call", name, [("num", float(i)) for i in ids], 0)


def _markers(model, ctx, a, keys):
    for key in keys:
        if a.get(key) is not None and a[key] not in model.markers:
            raise ctx.error(f"marker {a[key]} does not exist", key)


def _rigid(model, ctx, a, keys, what):
    """DeckError when a marker of `keys` is on a point body (it cannot take `what`)."""
    for key in keys:
        mid = a.get(key)
        if mid and model.bodies[model.markers[mid].body].kind == "point":
            raise ctx.error(f"{what} needs rigid bodies; marker {mid} is on point body "
                            f"{model.markers[mid].body}", key)


def _components(ctx, a):
    """The six (tree, text) components of a vector force, by its type."""
    kind = a.get("type") or "FORCEONLY"
    wanted = {"FORCEONLY": "f", "TORQUEONLY": "t", "FORCEANDTORQUE": "ft"}[kind]
    comps = []
    for lead in "ft":
        for c in "xyz":
            key = f"{lead}{c}_expression"
            e = a.get(key)
            if e is not None and lead not in wanted:
                raise ctx.error(f"a {kind} force has no {key}", key)
            comps.append(e if e is not None else (_ZERO, "0"))
    return comps


def add_vforce(model, ctx, a):
    """Validate one Force_Vector_TwoBody or Force_Vector_OneBody and add it."""
    ctx.id = a["id"]
    two = ctx.tag == "Force_Vector_TwoBody"
    at = "i_marker_id" if two else "marker_id"
    _markers(model, ctx, a, (at, "j_floating_marker_id", "ref_marker_id"))
    comps = _components(ctx, a)
    if any(tree != _ZERO for tree, _ in comps[3:]):
        _rigid(model, ctx, a, (at, "j_floating_marker_id"), "a torque")
    model.vforces[a["id"]] = VectorForce(
        a["id"], a[at], a["j_floating_marker_id"] if two else 0, a["ref_marker_id"] or 0,
        [e[0] for e in comps], [e[1] for e in comps], a["label"])
    model._where[("vforce", a["id"])] = ctx


def add_bushing(model, ctx, a):
    """Validate one Force_Bushing, add it and the vector force that holds its law."""
    ctx.id = bid = a["id"]
    _markers(model, ctx, a, ("i_marker_id", "j_marker_id"))
    i, j = a["i_marker_id"], a["j_marker_id"]
    if model.markers[i].body == model.markers[j].body:
        raise ctx.error(f"markers {i} and {j} are on one body: a bushing between them does "
                        "nothing", "j_marker_id")
    bushing = Bushing(bid, i, j, tuple(a[k] for k in STIFF), tuple(a[k] for k in DAMP),
                      tuple(a[k] for k in LOAD), a["label"])
    if any(v for v in bushing.stiffness[3:] + bushing.damping[3:] + bushing.preload[3:]):
        _rigid(model, ctx, a, ("i_marker_id", "j_marker_id"), "a bushing's torques")
    model.bushings[bid] = bushing
    measures = [("DX", (i, j, j)), ("DY", (i, j, j)), ("DZ", (i, j, j)),
                ("AX", (i, j)), ("AY", (i, j)), ("AZ", (i, j))]
    rates = [("VX", (i, j, j, j)), ("VY", (i, j, j, j)), ("VZ", (i, j, j, j)),
             ("WX", (i, j, j)), ("WY", (i, j, j)), ("WZ", (i, j, j))]
    trees, texts = [], []
    for n in range(6):
        par = [("param", f"Force_Bushing/{bid}/{names[n]}", values[n])
               for names, values in ((STIFF, bushing.stiffness), (DAMP, bushing.damping),
                                     (LOAD, bushing.preload))]
        # the angles small and projected (no turns tracked): AX..AZ's values in (-pi, pi]
        x = (_call(measures[n][0], *measures[n][1]) if n < 3 else
             ex.wrapped(measures[n][0], *measures[n][1]))
        rate = _call(rates[n][0], *rates[n][1])
        law = ("bin", "+", ("bin", "-", ("neg", ("bin", "*", par[0], x)),
                            ("bin", "*", par[1], rate)), par[2])
        trees.append(law)
        texts.append(f"-{STIFF[n]} {measures[n][0]}{measures[n][1]} - {DAMP[n]} "
                     f"{rates[n][0]}{rates[n][1]} + {LOAD[n]}")
    model.vforces[-bid] = VectorForce(-bid, i, j, j, trees, texts, a["label"])
    model._where[("vforce", -bid)] = ctx
    model._where[("bushing", bid)] = ctx
