"""Vector forces and bushings: Force_Vector_TwoBody, Force_Vector_OneBody and Force_Bushing,
all held as one kernel element (csrc/elements/vforce.c): a force and a torque by their
components in a reference marker's axes, on I's body at I and, for two bodies, opposite on
the other body at the same point.

A Force_Bushing (Adams BUSHING) is kept under its law key (-id: pysolver.records.law_key) of
the vector forces, its six components in J's axes (../shared/reference/elements.md section
4.2):

    F = -[kx DX, ky DY, kz DZ] - [cx VX, cy VY, cz VZ] + [fx0, fy0, fz0]
    T = -[ktx AX, kty AY, ktz AZ] - [ctx WX, cty WY, ctz WZ] + [tx0, ty0, tz0]

with DX = DX(I, J, J), VX = VX(I, J, J, J) (I's velocity relative to J seen from J), AX..AZ =
AX(I, J).. (single-axis angles: the small-angle convention, one large angle at most; Adams'
bushing page calls them "projected, small-angle rotational displacements": the values in
(-pi, pi], as AX..AZ in an expression, never tracked) and WX =
WX(I, J, J). The reaction on J's body at I's point is -F and -T, which is -F and
-T - d x F at J's origin. Its 18 numbers are sweep parameters (``Force_Bushing/<id>/kx``...).
"""
from ..records import Bushing, VectorForce, law_key
from . import expr as ex

#: A bushing's numbers: stiffness, damping, preload per component.
STIFF = ("kx", "ky", "kz", "ktx", "kty", "ktz")
DAMP = ("cx", "cy", "cz", "ctx", "cty", "ctz")
LOAD = ("preload_x", "preload_y", "preload_z", "preload_tx", "preload_ty", "preload_tz")
_ZERO = ("num", 0.0)


#: The deflections of I relative to J a bushing, field or beam reads (in J's axes, the
#: rotations AX..AZ: the small-angle convention) and their rates, by the markers' roles.
DEFLECTIONS = (("DX", "ijj"), ("DY", "ijj"), ("DZ", "ijj"), ("AX", "ij"), ("AY", "ij"),
               ("AZ", "ij"))
RATES = (("VX", "ijjj"), ("VY", "ijjj"), ("VZ", "ijjj"), ("WX", "ijj"), ("WY", "ijj"),
         ("WZ", "ijj"))


def measures(table, i, j):
    """[(tree, text)] of the six measures of `table` (DEFLECTIONS or RATES) of I and J; the
    angles small and projected (no turns tracked): AX..AZ's values in (-pi, pi]."""
    out = []
    for name, roles in table:
        ids = [i if r == "i" else j for r in roles]
        out.append((ex.call(name, *ids), f"{name}({', '.join(map(str, ids))})"))
    return out


def check_markers(model, ctx, a, keys):
    """DeckError when a marker of `keys` does not exist."""
    for key in keys:
        if a.get(key) is not None and a[key] not in model.markers:
            raise ctx.error(f"marker {a[key]} does not exist", key)


def check_rigid(model, ctx, a, keys, what):
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
    check_markers(model, ctx, a, (at, "j_floating_marker_id", "ref_marker_id"))
    comps = _components(ctx, a)
    if any(tree != _ZERO for tree, _ in comps[3:]):
        check_rigid(model, ctx, a, (at, "j_floating_marker_id"), "a torque")
    model.vforces[a["id"]] = VectorForce(
        a["id"], a[at], a["j_floating_marker_id"] if two else 0, a["ref_marker_id"] or 0,
        [e[0] for e in comps], [e[1] for e in comps], a["label"])
    model._where[("vforce", a["id"])] = ctx


def add_bushing(model, ctx, a):
    """Validate one Force_Bushing, add it and the vector force that holds its law."""
    ctx.id = bid = a["id"]
    check_markers(model, ctx, a, ("i_marker_id", "j_marker_id"))
    i, j = a["i_marker_id"], a["j_marker_id"]
    check_bodies(model, ctx, i, j, "a bushing")
    bushing = Bushing(bid, i, j, tuple(a[k] for k in STIFF), tuple(a[k] for k in DAMP),
                      tuple(a[k] for k in LOAD), a["label"])
    if any(v for v in bushing.stiffness[3:] + bushing.damping[3:] + bushing.preload[3:]):
        check_rigid(model, ctx, a, ("i_marker_id", "j_marker_id"), "a bushing's torques")
    model.bushings[bid] = bushing
    trees, texts = [], []
    for n, ((x, xt), (rate, rt)) in enumerate(zip(measures(DEFLECTIONS, i, j),
                                                  measures(RATES, i, j))):
        par = [("param", f"Force_Bushing/{bid}/{names[n]}", values[n])
               for names, values in ((STIFF, bushing.stiffness), (DAMP, bushing.damping),
                                     (LOAD, bushing.preload))]
        law = ("bin", "+", ("bin", "-", ("neg", ("bin", "*", par[0], x)),
                            ("bin", "*", par[1], rate)), par[2])
        trees.append(law)
        texts.append(f"-{STIFF[n]} {xt} - {DAMP[n]} {rt} + {LOAD[n]}")
    hold_law(model, ctx, "Force_Bushing", bid, i, j, trees, texts, a["label"])


def check_bodies(model, ctx, i, j, what):
    """DeckError when markers i and j are on one body (`what` between them does nothing)."""
    if model.markers[i].body == model.markers[j].body:
        raise ctx.error(f"markers {i} and {j} are on one body: {what} between them does "
                        "nothing", "j_marker_id")


def hold_law(model, ctx, tag, eid, i, j, trees, texts, label):
    """Add the vector force that holds element `eid` of `tag`: the six components `trees` in
    J's axes, on I's body at I, the opposite on J's body."""
    key = law_key(tag, eid)
    model.vforces[key] = VectorForce(key, i, j, j, trees, texts, label, (tag, eid))
    model._where[("vforce", key)] = ctx
    kind = {"Force_Bushing": "bushing", "Force_Field": "field", "Force_Beam": "beam"}[tag]
    model._where[(kind, eid)] = ctx
