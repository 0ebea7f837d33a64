"""User subroutines the kernel calls: C shared libraries, and Python routines that could not be
traced into expressions (a cffi callback with the same C calling convention).

Each routine is asked once, Adams-style, with iflag = 1 which system values it reads
(``ps_user_declare``); those become measure inputs of a ``PS_OP_USER`` tape instruction, so the
chain rule runs through the kernel's exact measure derivatives and only the routine's own
partials are differenced (csrc/usersub.c). The element's expression becomes the tree
``('user', routine, channel, [input trees])``.
"""
import dataclasses
import dis
import math
import threading
import types

from ..deck import expr as ex
from ..deck import tracer
from ..deck.usersubs import CONVENTIONS, elements, set_trees
from ..errors import ExpressionError
from .bindings import ffi, lib
from .userlib import open_routine

#: Runs at integr_tol of at least this take the routines' first partials by second-order
#: central differences, tighter runs by fourth-order ones (ps_user_point, psData.user_coarse):
#: the rounding noise of second-order differences, about 1e-11 relative, fails IDA's
#: corrector at tight tolerances (seed 3's penalties as C routines: the expression version's
#: steps and convergence failures down to 1e-9 in either order; at 1e-10 1.3-1.8x its steps
#: with second-order differences, its steps with fourth-order ones), and fourth-order ones
#: take twice the calls.
COARSE_TOL = 1e-9

_SIGNATURE = {lib.PS_USER_DFLAG: "void(int *, double *, double *, int *, int *, int *, double *)",
              lib.PS_USER_IORD: "void(int *, double *, double *, int *, int *, int *, double *)",
              lib.PS_USER_PLAIN: "void(int *, double *, double *, int *, int *, double *)"}
#: The C form of each argument list: a fifth argument dflag, iord (MOTSUB), or none.
_FORM = {"dflag": lib.PS_USER_DFLAG, "iord": lib.PS_USER_IORD, "iflag": lib.PS_USER_PLAIN}


@dataclasses.dataclass
class Routine:
    """One routine the kernel calls."""
    fn: object            # cdata void *: the C function, or a cffi callback
    form: int             # PS_USER_*
    id: int
    par: tuple
    keys: list            # canonical inputs, e.g. ["DX(9)", "DY(9)"]
    keep: object = None   # what must stay alive while the kernel may call fn
    timeless: bool = False    # never reads its time argument: not differenced in time
    name: str = ""        # the routine as the deck names it, for messages
    python: bool = False  # a Python routine: messages name py_sysfnc, py_syspar


def bind(model):
    """Give every element whose user subroutine is not an expression yet a kernel call."""
    for kind, el in elements(model):
        if (el.exprs[0] if kind == "request" else el.expr) is not None:
            continue
        ctx = model._where[(kind, el.id)]
        ctx.id = el.id
        sub = el.usersub
        form = _FORM[CONVENTIONS[ctx.tag][1][4]]
        if sub.library:
            fn, keep, how = _library(ctx, sub), None, f"C library {sub.library}"
            timeless = False
        else:
            fn, keep, timeless = _callback(ctx, sub, form, model)
            how = f"Python callback ({sub.untraced})"
        if len(sub.par) > 64:
            raise ctx.error("at most 64 USER(...) parameters", sub.attribute)
        keys = _declare(ctx, sub, fn, form, el.id, python=not sub.library)
        if kind == "motion" and keys:
            raise ctx.error(f"{sub.label} declares {', '.join(keys)}: a motion is a function "
                            "of time only", sub.attribute)
        iord = kind == "motion" and _honours_iord(ctx, sub, fn, el.id, not sub.library)
        if iord:
            timeless = 2                # the kernel asks it for its derivatives (iord 1, 2)
        if keep is not None:
            keep[1].keys = keys         # the Python routine reads them by name
        k = len(model.user_routines)
        model.user_routines.append(Routine(fn, form, el.id, tuple(sub.par), keys, keep,
                                           timeless, sub.label, not sub.library))
        inputs = [_key_tree(ctx, sub, key) for key in keys]
        nvalues = CONVENTIONS[ctx.tag][2]
        trees = [("user", k, chan, inputs) for chan in range(nvalues)]
        set_trees(model, kind, el, trees)
        model.usersub_paths[f"{ctx.tag} {el.id}"] = f"{sub.describe()}: {how}, called " \
            "from the kernel; " + (
                "its velocity and acceleration from the routine itself (iord = 1, 2)" if iord
                else "its velocity and acceleration by differences of its value in time (it "
                "ignores iord)" if kind == "motion" else
                f"its partials in {', '.join(keys + ([] if timeless else ['TIME'])) or 'nothing'}"
                + (" (not TIME: it never reads its time argument)" if timeless else "")
                + " by central differences, except those it gives with c_syspar / py_syspar")
    from ..deck.references import check_references
    check_references(model)


def _library(ctx, sub):
    fn, msg = open_routine(sub.library, sub.routine)
    if fn == ffi.NULL:
        raise ctx.error(f"cannot load {sub.routine} from {sub.library}: {msg}",
                        "usrsub_dll_name")
    return fn


def _declare(ctx, sub, fn, form, id, python):
    """The system values the routine reads, from its iflag call."""
    maxkeys = lib.PS_USER_MAXIN
    keys = ffi.new("char[]", maxkeys * lib.PS_USER_KEY)
    msg = ffi.new("char[256]")
    par = ffi.new("double[]", list(sub.par) or [0.0])
    n = lib.ps_user_declare(fn, form, int(python), id, par, len(sub.par), keys, maxkeys, msg,
                            256)
    if n < 0:
        # time and every value read are 0 in that call: the error is not about the state
        raise ctx.error(f"{sub.label} (iflag call, time and every value it reads 0): "
                        f"{ffi.string(msg).decode(errors='replace')}", sub.attribute)
    if n > maxkeys:
        raise ctx.error(f"{sub.label} reads more than {maxkeys} system values", sub.attribute)
    raw = ffi.buffer(keys)[:]
    return [raw[i * lib.PS_USER_KEY:(i + 1) * lib.PS_USER_KEY].split(b"\0")[0].decode()
            for i in range(n)]


#: Times at which a MOTSUB's iord answers are compared with differences of its value.
IORD_TIMES = (0.0, 0.375, 1.25)


def _honours_iord(ctx, sub, fn, id, python):
    """Whether a MOTSUB gives its velocity and acceleration when asked (iord = 1, 2), as Adams
    asks: False when it returns its value whatever iord says, or a non-finite number for
    iord 1 or 2; DeckError when its answers
    disagree with differences of its value (relative 1e-6 for the velocity, 1e-5 for the
    acceleration, at one of the steps 1e-2, 1e-3 / 16^s of max(1, |t|))."""
    par = ffi.new("double[]", list(sub.par) or [0.0])
    out, msg = ffi.new("double *"), ffi.new("char[256]")

    def f(t, iord):
        if lib.ps_user_motion(fn, int(python), id, par, len(sub.par), t, iord, out, msg,
                              256) != 0:
            raise ctx.error(f"{sub.label} (iord = {iord}, t = {t:g}): "
                            f"{ffi.string(msg).decode(errors='replace')}", sub.attribute)
        return out[0]

    answers = [(t, f(t, 0), f(t, 1), f(t, 2)) for t in IORD_TIMES]
    if all(v1 == v0 and v2 == v0 for _, v0, v1, v2 in answers) or \
            not all(math.isfinite(v) for _, _, v1, v2 in answers for v in (v1, v2)):
        return False                    # the value whatever iord is, or none for iord > 0
    for t, v0, v1, v2 in answers:
        for iord, given, tol in ((1, v1, 1e-6), (2, v2, 1e-5)):
            diffs = [_difference(f, t, v0, h, iord) for h in _iord_steps(t)]
            if not any(abs(given - d) <= tol * max(abs(given), abs(d)) + noise
                       for d, noise in diffs):
                raise ctx.error(f"{sub.label} gives {given:.10g} for iord = {iord} at t = "
                                f"{t:g}, but differences of its value give {diffs[1][0]:.10g}: "
                                "give the velocity (iord = 1) and acceleration (iord = 2), or "
                                "the value whatever iord is", sub.attribute)
    return True


def _iord_steps(t):
    scale = max(1.0, abs(t))
    return [1e-2 * scale] + [1e-3 * scale / 16 ** s for s in range(3)]


def _difference(f, t, v0, h, iord):
    """The fourth-order central difference of f(., 0) at t (first or second derivative), and
    a bound on its rounding noise."""
    p1, m1, p2, m2 = f(t + h, 0), f(t - h, 0), f(t + 2 * h, 0), f(t - 2 * h, 0)
    noise = 64 * 2.2e-16 * max(abs(v0), abs(p1), abs(m1), abs(p2), abs(m2)) / h ** iord
    if iord == 1:
        return (8 * (p1 - m1) - (p2 - m2)) / (12 * h), noise
    return (16 * (p1 + m1) - (p2 + m2) - 30 * v0) / (12 * h * h), noise


def _key_tree(ctx, sub, key):
    """The expression tree of a canonical key such as "DM(9,1)"."""
    name, _, rest = key.partition("(")
    ids = [float(v) for v in rest.rstrip(")").split(",") if v]
    node = ("call", name, [("num", v) for v in ids], 0)
    try:
        ex._check(node)
    except ExpressionError as err:
        raise ctx.error(f"{sub.label} reads {key}: {err.reason}", sub.attribute) from None
    return node


def _callback(ctx, sub, form, model):
    """A cffi callback running the Python routine with MotionSolve's Python arguments.

    Returns the callback, a :class:`_Reader`, whose ``keys`` :func:`bind` sets once the
    iflag call has declared them, and whether the routine never reads its time argument
    (:func:`reads_time`)."""
    from ..deck.usersubs import python_routine
    fn = python_routine(ctx, sub, model)
    nvalues = CONVENTIONS[ctx.tag][2]
    name = sub.label
    par = list(sub.par)
    reader = _Reader()
    plain = form == lib.PS_USER_PLAIN

    def call(id, time, dflag, iflag, value):
        prev = tracer.enter_live(reader.read, reader.syspar)
        try:
            reader.values = lib.ps_user_values()
            out = fn(id[0], time[0], list(par), len(par), iflag) if plain else \
                fn(id[0], time[0], list(par), len(par), dflag, iflag)
            if nvalues == 1:
                if out is None and not iflag:   # the iflag call's value is not used
                    raise tracer.RoutineError("returned None, not a number")
                value[0] = math.nan if out is None else float(out)
            else:
                for i, v in enumerate(list(out)[:nvalues]):
                    value[i] = float(v or 0.0)
        except BaseException as err:  # noqa: BLE001 - reported through the kernel, never raised
            text = f"{name}: {err}" if isinstance(err, (tracer.RoutineError,
                                                        tracer.SysfncError)) else \
                f"{name} raised {type(err).__name__}: {err}"
            lib.ps_user_fail(text.encode()[:190])
            value[0] = math.nan
        finally:
            tracer.leave_live(prev)

    if form == lib.PS_USER_DFLAG:
        def entry(id, time, par, npar, dflag, iflag, value):
            call(id, time, dflag[0], iflag[0], value)
    elif form == lib.PS_USER_IORD:
        def entry(id, time, par, npar, iord, iflag, value):
            call(id, time, iord[0], iflag[0], value)
    else:
        def entry(id, time, par, npar, iflag, value):
            call(id, time, 0, iflag[0], value)
    cb = ffi.callback(_SIGNATURE[form], entry)
    return ffi.cast("void *", cb), (cb, reader), not reads_time(fn)


#: Names whose use lets a function read its arguments without naming them.
_INTROSPECTION = frozenset({"locals", "vars", "eval", "exec", "_getframe", "currentframe",
                            "f_locals", "getargvalues", "stack"})


def reads_time(fn):
    """Whether the Python routine `fn` may read its second positional argument, time.

    False only for a plain function whose code provably never loads that argument: it is a
    named positional parameter, no instruction reads it, no nested function captures it and
    the code names nothing that reads a frame's locals (``locals``, ``vars``, ``eval``,
    ``exec``, frame inspection). Any other callable (a method, a partial, a decorated
    wrapper taking ``*args``, a builtin) is taken to read it. Its result then does not change
    with time at fixed inputs, so the kernel need not difference it in time.
    """
    if not isinstance(fn, types.FunctionType):
        return True
    code = fn.__code__
    if code.co_argcount < 2:
        return True
    name = code.co_varnames[1]
    if name in code.co_cellvars or _INTROSPECTION & set(code.co_names):
        return True
    # any instruction naming it but a plain store or delete counts as a read (superinstructions
    # such as 3.13's STORE_FAST_LOAD_FAST name two variables)
    for ins in dis.get_instructions(code):
        args = ins.argval if isinstance(ins.argval, tuple) else (ins.argval,)
        if name in args and ins.opname not in ("STORE_FAST", "DELETE_FAST"):
            return True
    return False


class _Reader:
    """py_sysfnc inside a kernel call: the declared values straight from the kernel's array,
    by (function, ids); anything else goes through c_sysfnc, which records it while declaring
    and reports an undeclared read as the routine's error."""

    def __init__(self):
        self.index, self.values = {}, ffi.NULL

    @property
    def keys(self):
        return self.index

    @keys.setter
    def keys(self, keys):
        """The canonical keys ("DX(9)") in declaration order."""
        for i, key in enumerate(keys):
            name, _, rest = key.partition("(")
            ids = tuple(int(v) for v in rest.rstrip(")").split(",") if v)
            self.index[(name, ids)] = i

    def read(self, fnc, ids):
        i = self.index.get((fnc, tuple(ids))) if self.values != ffi.NULL else None
        if i is None:
            return _c_sysfnc(fnc, ids)
        return [self.values[i], 0]

    def syspar(self, fnc, ids, partials):
        """py_syspar: the partial in one declared value straight to the kernel by its key;
        anything else (an array, a count that is wrong, a value not declared) through
        c_syspar, which takes or words it."""
        i = self.index.get((fnc, tuple(ids)))
        if i is not None and len(partials) == 1:
            lib.ps_user_give(i, float(partials[0]))
            return 0
        return _c_syspar(fnc, ids, partials)


_REQUESTS = {}                     # (fnc, ids) -> its C arguments, made once
_OUT = threading.local()           # per thread: what c_sysfnc and c_syspar write and read


def _request(fnc, ids):
    """The C arguments (name, ids, their count) of a read of (fnc, ids), made once."""
    ints = [int(i) for i in ids]
    req = _REQUESTS[(fnc, tuple(ids))] = (str(fnc).upper().encode(),
                                          ffi.new("int[]", ints or [0]), len(ints))
    return req


def _c_sysfnc(fnc, ids):
    """What c_sysfnc gives the routine for (fnc, ids)."""
    req = _REQUESTS.get((fnc, tuple(ids))) or _request(fnc, ids)
    out = getattr(_OUT, "v", None)
    if out is None:
        out = _OUT.v = (ffi.new("double *"), ffi.new("int *"))
    state, err = out
    lib.c_sysfnc(req[0], req[1], req[2], state, err)
    return [state[0], err[0]]


def _c_syspar(fnc, ids, partials):
    """py_syspar inside a kernel call: c_syspar with the routine's partials; its errflg."""
    req = _REQUESTS.get((fnc, tuple(ids))) or _request(fnc, ids)
    out = getattr(_OUT, "p", None)
    if out is None:
        out = _OUT.p = (ffi.new("double[6]"), ffi.new("int *"))
    buf, err = out
    values = [float(v) for v in partials]
    n = len(values)
    buf[0:min(n, 6)] = values[:6]
    lib.c_syspar(req[0], req[1], req[2], buf, n, err)
    return err[0]
