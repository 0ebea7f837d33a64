"""Checks of the references between elements: every id an expression names exists, no
cycles of VARVAL, PFORCE and SFORCE references, and penalty constraints g(q, t) use
displacement measures only."""
from .. import catalogue
from . import expr as ex
from .floating import placed, unplaced
from .splinedata import FEWEST


def check_references(model):
    """Every id an expression names must exist; penalty g must depend on displacements only."""
    tables = {"marker": model.markers, "variable": model.variables,
              "penalty": model.penalties, "sforce": model.sforces,
              "evaluate": model.evaluates, "motion": model.motions, "joint": model.joints,
              "body": model.bodies, "springdamper": model.springdampers,
              "bushing": model.bushings, "field": model.fields, "beam": model.beams,
              "spline": model.splines}
    where = model._where
    for se in model.sensors.values():
        if se.evaluate_id is not None and se.evaluate_id not in model.evaluates:
            ctx = where[("sensor", se.id)]
            ctx.id = se.id
            raise ctx.error(f"Sensor_Evaluate {se.evaluate_id} does not exist", "evaluate_id")
    items = list(_expressions(model))
    for key, attr, tree in items:
        ctx = where[key]
        ctx.id = key[1]
        for kind, ids in ex.references(tree).items():
            for i in sorted(ids):
                if i not in tables[kind] and ("elemental", key[1]) in where and \
                        key[0] == "request":
                    raise ctx.error(f"{kind} {i} does not exist", "elem_id")
                if i not in tables[kind]:
                    raise ctx.error(f"the expression refers to {kind} id {i}, which does not "
                                    "exist", attr)
                if kind == "marker" and unplaced(model, i):
                    raise ctx.error(unplaced(model, i), attr)
    # each interpolation function has the points it needs
    for key, attr, tree in items:
        for n in ex.nodes(tree):
            if n[0] == "call" and n[1] in FEWEST:
                sp = model.splines[int(n[2][2][1])]
                ctx = where[key]
                ctx.id = key[1]
                if len(sp.x) < FEWEST[n[1]]:
                    raise ctx.error(f"{n[1]} needs at least {FEWEST[n[1]]} points; "
                                    f"Reference_Spline {sp.id} has {len(sp.x)}", attr)
                if sp.z and len(n[2]) > 3:
                    raise ctx.error(f"{n[1]} takes no derivative order on a surface "
                                    f"(Reference_Spline {sp.id} has z values)", attr)
    # variable cycles and penalty dependence on velocities
    for key, attr, tree in items:
        ctx = where[key]
        ctx.id = key[1]
        try:
            dyn = _dynamic(model, tree, ())
        except _Cycle as cyc:
            chain = cyc.args[0]
            if all(name == "VARVAL" for name, _ in chain):
                what = "VARVAL cycle through variables " + " -> ".join(str(i) for _, i in chain)
            else:
                what = "the expressions refer to each other in a cycle: " + \
                    " -> ".join(f"{name}({i})" for name, i in chain)
            raise ctx.error(what, attr) from None
        if key[0] == "penalty" and dyn:
            raise ctx.error("a penalty constraint g(q, t) may use displacement measures only "
                            f"(found {dyn}); velocities enter through penalty1", attr)
        if key[0] in ("motion", "loadcontrol"):
            reads = time_only(tree, model)
            if reads:
                raise ctx.error(_not_timed(model, key, reads), attr)
        if key[0] == "gcon":
            late = sorted({n[1] for n in ex.nodes(tree) if n[0] == "call" and n[1] in
                           catalogue.FUNCTIONS and catalogue.FUNCTIONS[n[1]].reads
                           & {"accelerations", "forces"}})
            if late:
                raise ctx.error("a Constraint_General may read displacements, velocities "
                                f"and time (found {', '.join(late)})", attr)
            if dyn and not velocity_level(model.gcons[key[1]]):
                raise ctx.error(f"the expression reads velocities ({dyn}) through another "
                                "element (VARVAL, PFORCE or SFORCE): a non-holonomic "
                                "Constraint_General names its velocity measures in its own "
                                "expression", attr)


def _expressions(model):
    """(key, attribute, tree) of every expression in the model; a user subroutine's traced
    expression is named by its routine attribute, and one not traced yet is left out."""
    # a LoadControl's own motion is not the deck's: its Load_Function is
    motions = {i: mo for i, mo in model.motions.items() if i > 0}
    for kind, table in (("penalty", model.penalties), ("gcon", model.gcons),
                        ("motion", motions), ("sforce", model.sforces),
                        ("variable", model.variables), ("sensor", model.sensors),
                        ("evaluate", model.evaluates)):
        for el in table.values():
            if el.expr is not None:
                sub = getattr(el, "usersub", None)
                yield (kind, el.id), sub.attribute if sub else "expr", el.expr
    for lc in model.controls.values():
        yield ("loadcontrol", lc.id), "load_function", lc.load_expr
    for vf in model.vforces.values():
        for c, e in zip(("fx", "fy", "fz", "tx", "ty", "tz"), vf.exprs):
            yield ("vforce", vf.id), f"{c}_expression", e
    for r in model.requests.values():
        for k, e in enumerate(r.exprs):
            if e is not None:
                yield ("request", r.id), r.usersub.attribute if r.usersub else f"expr{k + 1}", e


def unwrapped_angles(model):
    """The (name, i, j) of every AXU, AYU, AZU call (MotionSolve's unwrapped AX, AY, AZ) in
    the model's expressions, name AX, AY or AZ, sorted: each is an angle tracked through its
    turns, one state per name and pair of markers."""
    found = set()
    for _, _, tree in _expressions(model):
        for n in ex.nodes(tree):
            if n[0] == "call" and n[1] in ex.TRACKED_ANGLES:
                ids = [placed(model, int(a[1])) for a in n[2]] + [0]
                found.add((n[1][:2], ids[0], ids[1]))
    return sorted(found)


def velocity_level(gc):
    """Whether Constraint_General `gc` names velocity measures: non-holonomic, held at the
    velocity level alone (csrc/elements/gcon.c)."""
    return gc.expr is not None and any(
        n[0] == "call" and n[1] in catalogue.FUNCTIONS
        and "velocities" in catalogue.FUNCTIONS[n[1]].reads for n in ex.nodes(gc.expr))


def time_only(tree, model, stack=()):
    """What makes an expression tree depend on more than time: the names of the functions
    of the state it calls (empty: it depends on time only).

    A spline (AKISPL, CUBSPL, ...) reads only its Reference_Spline's data and its x and z
    arguments (nodes of the tree too); VARVAL(id) is what its variable's expression is
    (named ``VARVAL(id), which reads ...`` when that reads the state). A variable that does
    not exist or closes a cycle counts as nothing here (check_references names either); one
    of a user subroutine not traced yet counts once it is (check_references runs again).
    """
    found = set()
    for n in ex.nodes(tree):
        if n[0] != "call" or n[1] not in ex.ID_ARGS or n[1] in ex.SPLINES:
            continue
        if n[1] == "VARVAL":
            vid = int(n[2][0][1])
            var = model.variables.get(vid)
            if var is None or var.expr is None or vid in stack:
                continue
            inner = time_only(var.expr, model, stack + (vid,))
            if inner:
                found.add(f"VARVAL({vid}), which reads {', '.join(sorted(inner))}")
            continue
        found.add(n[1])
    return found


def _not_timed(model, key, reads):
    """The message refusing a motion or Load_Function that depends on more than time."""
    reads = ", ".join(sorted(reads))
    if key[0] == "loadcontrol":
        return f"Load_Function must depend on time only; it reads {reads}"
    sub = model.motions[key[1]].usersub
    if sub is not None:
        return f"{sub.label} must give a function of time only; it reads {reads}"
    return f"a motion's expression must depend on time only; it reads {reads}"


class _Cycle(Exception):
    pass


#: Functions that read velocities, accelerations or forces (not a function of q and t).
_DYNAMIC = {name for name, f in catalogue.FUNCTIONS.items() if f.reads & catalogue.DYNAMIC}


def _dynamic(model, node, stack):
    """Return the name of a velocity-dependent function used by the tree, or None (a user
    subroutine not traced yet counts as nothing until it is)."""
    if node is None:
        return None
    tag = node[0]
    if tag == "user":
        for a in node[3]:
            r = _dynamic(model, a, stack)
            if r:
                return r
        return None
    if tag == "neg":
        return _dynamic(model, node[1], stack)
    if tag == "bin":
        return _dynamic(model, node[2], stack) or _dynamic(model, node[3], stack)
    if tag == "call":
        name, args = node[1], node[2]
        if name in ("VARVAL", "PFORCE", "SFORCE"):
            ref = (name, int(args[0][1]))
            if ref in stack:
                raise _Cycle(stack[stack.index(ref):] + (ref,))
            table = {"VARVAL": model.variables, "PFORCE": model.penalties,
                     "SFORCE": model.sforces}[name]
            inner = _dynamic(model, table[ref[1]].expr, stack + (ref,))
            return name if name in _DYNAMIC else inner
        if name in _DYNAMIC:
            return name
        if name not in ex.ID_ARGS:
            for a in args:
                r = _dynamic(model, a, stack)
                if r:
                    return r
    return None

