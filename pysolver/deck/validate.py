"""Raw deck elements -> a validated :class:`~pysolver.model.Model`.

:func:`build_model` checks every element against the schema, resolves ids, marker frames and
bodies (:mod:`.bodies`), the force-like elements and commands (here), and every reference an
expression makes (:mod:`.references`). Both deck formats end here, so they build identical
models.
"""
import math

import numpy as np

from ..errors import DeckError
from ..model import (
    Evaluate,
    Graphic,
    Model,
    Penalty,
    Request,
    ScalarForce,
    Sensor,
    Simulate,
    Static,
    Variable,
)
from ..options import DECK_NAMES, Options, rule_problem, steps_problem
from . import units as un
from . import usersubs
from .bodies import add_bodies
from .fields import add_beam, add_field
from .floating import place_floating
from .joints import add_coupler, add_gcon, add_joint
from .motions import add_joint_motion, add_motion, check_static_motions
from .references import check_references
from .requests import elemental_channels, marker_channels
from .schema import _ID_KIND, CANONICAL, SCHEMA, Ctx, attributes
from .splinedata import add_spline
from .springs import add_springdamper, fixed_line
from .tasks import add_loadcontrol
from .unmodelled import not_in_schema
from .vectors import add_bushing, add_vforce


def build_model(elements, source):
    """Validate raw elements and return a :class:`Model`.

    Parameters
    ----------
    elements : list of (tag, attrs, line, names)
        ``tag`` any capitalisation of an element name; ``attrs`` maps lower-case attribute
        names to raw values; ``names`` maps attribute names to how the deck spelled them.
    source : Source
    """
    model = Model(source)
    seen = {}
    markers_raw = {}
    bodies_raw = []
    later = []
    once = {}
    sim_t = 0.0
    for tag, attrs, line, names in elements:
        canon = CANONICAL.get(tag.lower())
        if canon is None:           # a DeckError, or a DeckWarning for one set aside
            not_in_schema(Ctx(source.file, tag, attrs, line, names))
            continue
        ctx = Ctx(source.file, canon, attrs, line, names)
        a = attributes(ctx)
        kind = _ID_KIND.get(canon)
        if kind:
            key = (kind, a["id"])
            if key in seen:
                raise ctx.error(f"duplicate {kind} id {a['id']} (first defined "
                                f"{_at(seen[key], ctx)})", "id")
            seen[key] = (ctx.file, line)
        if canon == "Units":
            model.units = {k: a[k] for k in ("mass", "length", "time", "force")}
            model.force_scale = un.force_scale(**model.units)
            model.has_units = True
        elif canon == "Force_Gravity":
            _once(ctx, once, "Force_Gravity")
            model.gravity = _gravity(ctx, a)
        elif canon == "Reference_Marker":
            markers_raw[a["id"]] = (ctx, a)
        elif canon in ("Body_Rigid", "Body_Point"):
            bodies_raw.append((ctx, a))
        elif canon == "Param_Static":
            _once(ctx, once, "Param_Static")
            model.static = Static(**{k: a[k] for k in SCHEMA["Param_Static"] if k != "label"})
        elif canon == "Param_Transient":
            _once(ctx, once, "Param_Transient")
            model.transient = _transient(ctx, a)
        elif canon == "Simulate":
            sim_t = _simulate(ctx, a, model, sim_t)
        elif canon == "Stop":
            break
        elif canon in ("ResOutput", "H3DOutput"):
            model.output_settings.setdefault(canon, {}).update(a)
        else:
            later.append((ctx, a))
    add_bodies(model, bodies_raw, markers_raw)
    for cmd in model.commands:
        if cmd.analysis == "QUASI-STATIC" and model.static.method == "MKEAM":
            raise DeckError("MKEAM does not do quasi-static analyses (seed 004); use FIM_D or FIM_S"
                            " in Param_Static", file=cmd.file, line=cmd.line, element="Simulate",
                            attribute="analysis_type")
    after = ("Motion_Joint", "Constraint_Coupler")
    for ctx, a in later:
        if ctx.tag not in after:
            _force_like(model, ctx, a)
    for ctx, a in later:                # after the joints they drive or couple
        if ctx.tag == "Motion_Joint":
            add_joint_motion(model, ctx, a)
        elif ctx.tag == "Constraint_Coupler":
            add_coupler(model, ctx, a)
    place_floating(model)
    check_static_motions(model)
    check_references(model)
    if not model.commands:
        model.commands.append(Simulate("TRANSIENT", 1.0, 0.01))
        model.default_command = True
    _check_intervals(model)
    model._freeze()
    return model


#: Largest magnitude of a gravity component, in any unit system (9.81 m/s^2 is 9.81e9 nm/s^2):
#: past it forces and accelerations are beyond what the integrator can carry.
MAX_GRAVITY = 1e20


def _once(ctx, once, tag):
    """A settings element given twice would silently let the later one win: refuse it."""
    if tag in once:
        raise ctx.error(f"a second {tag} (the first is {_at(once[tag], ctx)}; in a Python "
                        "deck INTEGRATOR, EQUILIBRIUM or ACCGRAV); give one")
    once[tag] = (ctx.file, ctx.line)


def _at(where, ctx):
    """'on line N' of an earlier element at where = (file, line), or 'at file:line' in another
    file (a command file's command against its dataset's statement)."""
    return f"on line {where[1]}" if where[0] == ctx.file else "at {}:{}".format(*where)


def value_rule(tag, attr, value):
    """The rule a number breaks beyond its attribute's kind (the text after "got ...; "), or
    None: the one check of a value, from a deck or a sweep case (pysolver.build.params)."""
    if tag == "Param_Transient":
        problem = rule_problem(attr, value)
        return f"expected a value {problem}" if problem else None
    if tag == "Force_Gravity" and abs(value) > MAX_GRAVITY:
        return (f"expected |{attr}| <= {MAX_GRAVITY:g} (in any unit system gravity is far "
                "smaller)")
    return None


def _gravity(ctx, a):
    for attr in ("grav_x", "grav_y", "grav_z"):
        problem = value_rule("Force_Gravity", attr, a[attr])
        if problem:
            raise ctx.error(f"got {a[attr]:g}; {problem}", attr)
    return np.array([a["grav_x"], a["grav_y"], a["grav_z"]])


def _transient(ctx, a):
    """Param_Transient as Options, each value checked by its option's rule, h_min by h_max."""
    given = {k: a[k] for k in DECK_NAMES if a[k] is not None}
    problems = [(name, f"got {val:g}; {why}") for name, val in given.items()
                if (why := value_rule("Param_Transient", name, val))]
    problems.append(("h_min", steps_problem(given.get("h_min"), given.get("h_max"))))
    name, problem = problems[0]
    if problem:
        raise ctx.error(problem, name)
    return Options(**given)


def _check_intervals(model):
    """A sensor's dt and a LoadControl's UpdateTime obey the rule of a print interval: at most
    MAX_ROWS rows (updates) in one command."""
    spans = [(c.end_time - t0) for c, t0 in zip(model.commands, _starts(model.commands))
             if c.analysis == "TRANSIENT"]
    longest = max(spans, default=0.0)
    items = [("sensor", s.id, s.dt, "dt") for s in model.sensors.values() if s.dt is not None]
    items += [("loadcontrol", c.id, c.update_time, "updatetime")
              for c in model.controls.values()]
    for kind, eid, dt, attr in items:
        rows = longest / dt
        if not rows < MAX_ROWS:
            ctx = model._where[(kind, eid)]
            what = "output rows" if kind == "sensor" else "controller updates"
            raise ctx.error(f"{longest:g} s every {dt:g} s would be {rows:.3g} {what}; at "
                            f"most {MAX_ROWS:.0e} per command", attr)


def _elemental(a):
    """Whether Post_Request attributes `a` make (or belong to) an ELEMENTAL_FORCE request."""
    return a["type"] == "ELEMENTAL_FORCE" or any(
        a[k] is not None for k in ("elem_type", "elem_id", "jflag"))


def _starts(commands):
    t = 0.0
    for c in commands:
        yield t
        t = c.end_time


#: Most output rows one Simulate command may ask for (a memory budget applies at run time).
MAX_ROWS = 1e9

#: Shortest transient command, relative to |end_time| and absolute (time units): IDA's first
#: step is a fraction of the command and must stay far above rounding of the time and far
#: from underflow (1e-300 fails in IDA).
MIN_SPAN = 1e-12
MIN_DURATION = 1e-30


def given_span(a):
    return "duration" if a["duration"] is not None else "end_time"


def _check_start(ctx, a, model, t_prev):
    """start_time, when given, is where the run is: 0 before the first command (a run starts
    at TIME = 0, docs/deck-language.md's Simulate row), the previous command's end after."""
    start = a["start_time"]
    if start is None or abs(start - t_prev) <= 1e-12:
        return
    if not model.commands:
        raise ctx.error(f"got {start:g}; a run starts at TIME = 0 (pysolver has no other "
                        f"start time): leave {ctx.named('start_time')} out or give 0",
                        "start_time")
    raise ctx.error(f"{ctx.named('start_time')} must equal the time the previous command "
                    f"ended ({t_prev:g})", "start_time")


def _simulate(ctx, a, model, t_prev):
    _check_start(ctx, a, model, t_prev)
    if a["analysis_type"] == "ASSEMBLY":
        # the initial-conditions analysis alone: positions and velocities made to satisfy the
        # joints and motions with the least change, one output row, at the current time
        given = [k for k in ("end_time", "duration", "print_interval", "num_step",
                             "print_increment") if a[k] is not None]
        if given:
            raise ctx.error("an Assembly analysis takes no end time or output interval",
                            given[0])
        model.commands.append(Simulate("ASSEMBLY", t_prev, 0.0, ctx.line, ctx.file))
        return t_prev
    if a["analysis_type"] == "STATIC":
        # an equilibrium at the current time, or at end_time when given
        given = [k for k in ("duration", "print_interval", "num_step", "print_increment")
                 if a[k] is not None]
        if given:
            raise ctx.error("a Static analysis takes no duration or output interval", given[0])
        end = t_prev if a["end_time"] is None else a["end_time"]
        if end < t_prev:
            raise ctx.error(f"{ctx.named('end_time')} {end:g} is before the current time "
                            f"{t_prev:g}", "end_time")
        model.commands.append(Simulate("STATIC", end, 0.0, ctx.line, ctx.file))
        return end
    if (a["end_time"] is None) == (a["duration"] is None):
        raise ctx.error(f"give exactly one of {ctx.named('end_time')} and "
                        f"{ctx.named('duration')}", "end_time")
    end = a["end_time"] if a["end_time"] is not None else t_prev + a["duration"]
    if end <= t_prev:
        raise ctx.error(f"{ctx.named('end_time')} {end:g} must be after the start time "
                        f"{t_prev:g}", "end_time")
    given = [k for k in ("print_interval", "num_step", "print_increment") if a[k] is not None]
    if len(given) > 1:
        named = [ctx.named(k) for k in given]
        raise ctx.error(f"give one of {', '.join(named[:-1])} and {named[-1]}", given[1])
    if a["print_interval"] is not None:
        dt = a["print_interval"]
    elif a["num_step"] is not None:
        dt = (end - t_prev) / a["num_step"]
    else:
        dt = (end - t_prev) / 100.0
    if a["print_increment"] is not None:
        ctx.warn(f"{ctx.named('print_increment')} = {a['print_increment']} is not used: "
                 "pysolver prints at fixed times, never every n integrator steps; this "
                 f"command prints every {dt:g} (100 intervals; give print_interval or "
                 "num_step)", "print_increment")
    span = end - t_prev
    shortest = max(MIN_SPAN * abs(end), MIN_DURATION)
    if not span >= shortest:
        raise ctx.error(f"the command lasts {span:g}; expected at least {shortest:g} "
                        f"({MIN_SPAN:g} of |end_time|, and {MIN_DURATION:g}): IDA cannot "
                        "take a first step in less", given_span(a))
    rows = (end - t_prev) / dt
    if not math.isfinite(end - t_prev) or not rows < MAX_ROWS:
        raise ctx.error(f"{end - t_prev:g} s every {dt:g} s would be {rows:.3g} output rows; "
                        f"at most {MAX_ROWS:.0e} per command", given[0] if given else "end_time")
    model.commands.append(Simulate(a["analysis_type"], end, dt, ctx.line, ctx.file))
    return end


def _parsed(val):
    return val if val is None else val[0]


def _is_user(val):
    """True for a converted expr attribute holding USER(...) parameters."""
    return val is not None and val[0][0] == "user"


def _expression(model, ctx, a, key="expr"):
    """(tree, text, usersub) of an element that takes an expression or a user subroutine."""
    usersub = usersubs.from_attributes(model, ctx, a)
    if usersub is not None:
        return None, usersub.describe(), usersub
    if _is_user(a.get(key)):
        raise usersubs.no_routine(ctx, key)
    if a.get(key) is None:
        raise ctx.error("missing required attribute for type EXPRESSION", key)
    return a[key][0], a[key][1], None


#: The forces held as a scalar or vector force, each added by its module's function.
_FORCES = {"Force_SpringDamper": add_springdamper, "Force_Vector_TwoBody": add_vforce,
           "Force_Vector_OneBody": add_vforce, "Force_Bushing": add_bushing,
           "Force_Field": add_field, "Force_Beam": add_beam}


def _force_like(model, ctx, a):
    ctx.id = a.get("id")
    tag = ctx.tag
    if tag == "Force_Penalty":
        tree, text, sub = _expression(model, ctx, a)
        model.penalties[a["id"]] = Penalty(a["id"], tree, text, a["penalty"], a["penalty1"],
                                           a["unilateral"], a["smoothing_factor"], a["label"],
                                           sub)
        model._where[("penalty", a["id"])] = ctx
    elif tag == "Force_Scalar_TwoBody":
        sub = usersubs.from_attributes(model, ctx, a)
        if sub is not None:
            tree, text = None, sub.describe()
        else:
            given = [k for k in ("expr", "val_expression", "val") if a[k] is not None]
            if len(given) != 1:
                raise ctx.error("give exactly one of expr, val_expression and val", "expr")
            tree, text = a[given[0]] if given[0] != "val" else (("num", a["val"]), repr(a["val"]))
            if tree[0] == "user":
                raise ctx.error("USER(...) calls a user subroutine: give the routine "
                                "(script_name, or ROUTINE= in a Python deck)", given[0])
        for key, body in (("i_marker_id", "body1_id"), ("j_marker_id", "body2_id")):
            if a[key] not in model.markers:
                raise ctx.error(f"marker {a[key]} does not exist", key)
            if a[body] not in (None, model.markers[a[key]].body):
                raise ctx.error(f"got {a[body]}, but {ctx.named(key)} {a[key]} is on body "
                                f"{model.markers[a[key]].body}", body)
        fixed_line(ctx, model, a)
        model.sforces[a["id"]] = ScalarForce(a["id"], a["type"] == "TORQUE", a["i_marker_id"],
                                             a["j_marker_id"], tree, text, a["label"], sub,
                                             action_only=a["is_action_only"])
        model._where[("sforce", a["id"])] = ctx
    elif tag == "Reference_Spline":
        add_spline(model, ctx, a)
    elif tag == "Post_Graphic":
        for key, v in a.items():             # every *marker_id / *_id names a marker
            if key.endswith("marker_id") and v is not None:
                try:
                    mid = int(v)
                except ValueError:
                    raise ctx.error(f"got {v!r}; expected a marker id", key) from None
                if mid not in model.markers:
                    raise ctx.error(f"marker {mid} does not exist", key)
        model.graphics[a["id"]] = Graphic(a["id"], a["type"], {
            k: v for k, v in a.items() if k not in ("id", "type", "label")}, a["label"])
        model._where[("graphic", a["id"])] = ctx
    elif tag in _FORCES:
        _FORCES[tag](model, ctx, a)
    elif tag == "Motion_Marker":
        add_motion(model, ctx, a)
    elif tag in ("Constraint_Joint", "Constraint_Jprim"):
        add_joint(model, ctx, a)
    elif tag == "Constraint_General":
        add_gcon(model, ctx, a)
    elif tag == "LoadControl":
        add_loadcontrol(model, ctx, a)
    elif tag == "Reference_Variable":
        tree, text, sub = _expression(model, ctx, a)
        model.variables[a["id"]] = Variable(a["id"], tree, text, a["label"], sub)
        model._where[("variable", a["id"])] = ctx
    elif tag == "Sensor_Event":
        tree, text, sub = _expression(model, ctx, a)
        zc = a["zero_crossing"]
        if zc is not None and not 0 < zc < 1:
            raise ctx.error(f"got {zc:g}; expected 0 < zero_crossing < 1", "zero_crossing")
        compare = "LT" if a["compare"] == "LE" else a["compare"]
        model.sensors[a["id"]] = Sensor(a["id"], tree, text, a["value"], compare,
                                        a["error_tol"], a["evaluate_id"], a["dt"],
                                        a["stepsize"], zc, a["hmax"], a["halt"], a["print"],
                                        a["restart"], a["verbose"], a["return"], a["label"], sub)
        model._where[("sensor", a["id"])] = ctx
    elif tag == "Sensor_Evaluate":
        tree, text, sub = _expression(model, ctx, a)
        model.evaluates[a["id"]] = Evaluate(a["id"], tree, text, a["label"], sub)
        model._where[("evaluate", a["id"])] = ctx
    elif tag == "Post_Request" and (a["type"].startswith("MARKER_") or _elemental(a)):
        for key in ("usrsub_param_string", "script_name", "usrsub_dll_name"):
            if a.get(key) is not None:
                raise ctx.error(f"{key} belongs to a USERSUB request, not {a['type']}", key)
        channels = elemental_channels if _elemental(a) else marker_channels
        trees, texts, names = channels(ctx, a, model.markers)
        model.requests[a["id"]] = Request(a["id"], trees, texts, names, a["label"], None)
        model._where[("request", a["id"])] = ctx
        if _elemental(a):
            model._where[("elemental", a["id"])] = ctx
    elif tag == "Post_Request":
        sub = usersubs.from_attributes(model, ctx, a)
        exprs = [a[f"expr{k}"] for k in range(1, 9)]
        if sub is not None:
            exprs = [None] * 8
        for k, e in enumerate(exprs):
            if _is_user(e):
                raise usersubs.no_routine(ctx, f"expr{k + 1}")
        model.requests[a["id"]] = Request(a["id"], [_parsed(e) for e in exprs],
                                          [e[1] if e else None for e in exprs],
                                          [a[f"name{k}"] for k in range(1, 9)], a["label"], sub)
        model._where[("request", a["id"])] = ctx
