"""User subroutines (``type="USERSUB"``): PFOSUB, SENSUB, SEVSUB, VARSUB, SFOSUB, REQSUB,
MOTSUB, GCOSUB.

At load (:func:`from_attributes`) the attributes are checked without running anything: the
routine's script or library exists, a script defines the function with the conventional
arguments. When the model is first compiled (:func:`resolve`) each Python routine is traced
into an expression tree (:mod:`.tracer`) that replaces the element's expression, so it runs in
the kernel like one; a routine that cannot be traced, and a C library's, are called from the
kernel instead (:mod:`pysolver.build.usercalls`). Loading an XML deck therefore never executes
code; running it executes its scripts and loads its libraries.
"""
import ast
import dataclasses
import os
import sys
import traceback
import types

import numpy as np

from .. import catalogue, settings
from ..errors import DeckError, ExpressionError
from ..model import UserSub
from . import elfsyms, statecheck, tracelib, tracer
from . import expr as ex

#: Element -> (conventional routine name, its Python arguments, values it returns).
CONVENTIONS = {tag: e.usersub for e in catalogue.ELEMENTS if e.usersub for tag in e.tags}
_KIND = {tag: e.kind for e in catalogue.ELEMENTS if e.usersub for tag in e.tags}
_ATTRS = ("usrsub_dll_name", "usrsub_fnc_name", "usrsub_param_string", "script_name",
          "interpreter")


def from_attributes(model, ctx, a):
    """The element's UserSub, or None when it is defined by an expression; DeckError on bad
    attributes. Nothing is executed."""
    given = [k for k in _ATTRS if a.get(k) is not None]
    user_expr = a.get("expr") is not None and a["expr"][0][0] == "user"
    if ctx.tag in ("Force_Scalar_TwoBody", "Constraint_General"):  # no type=USERSUB there
        wanted = bool(given) or user_expr
    else:
        wanted = a.get("type") == "USERSUB"
        if not wanted and given:
            raise ctx.error("is used only with type=\"USERSUB\"", given[0])
    if not wanted:
        return None
    if not model.source.user_code:
        where = next((k for k in ("script_name", "usrsub_dll_name", "usrsub_fnc_name")
                      if a.get(k) is not None), "type")
        raise ctx.error("a user subroutine would run code the deck names, and user_code=False "
                        "refuses it (--no-user-code)", where)
    name, args, _ = CONVENTIONS[ctx.tag]
    if a.get("interpreter") == "MATLAB":
        raise ctx.error("MATLAB user subroutines are not supported; write the routine in "
                        "Python (script_name, interpreter=\"PYTHON\")", "interpreter")
    if a.get("usrsub_param_string") is not None:
        par = a["usrsub_param_string"]
    elif user_expr:
        par = a["expr"][0][1]
    elif a.get("expr") is not None:
        if ctx.named("expr") != "expr":     # a Python or Adams statement: its keywords
            raise ctx.error(f"a user subroutine takes its parameters as {ctx.named('expr')}="
                            "\"USER(...)\", not an expression", "expr")
        raise ctx.error("with type=\"USERSUB\" the parameters go in usrsub_param_string="
                        "\"USER(...)\", not an expression", "expr")
    else:
        par = ()
    routine = a.get("usrsub_fnc_name") or name
    if isinstance(routine, str) and routine.strip().upper() == "NULL":
        routine = name                  # MotionSolve: "NULL" is the conventional name
    if isinstance(routine, str) and ("::" in routine or "\u2237" in routine):
        # MotionSolve's ROUTINE="path/lib.so::function" names a C library and its function;
        # Adams' "lib::" its conventional one (SFOSUB, ...)
        library, _, routine = routine.replace("\u2237", "::").rpartition("::")
        a = dict(a, usrsub_dll_name=library)
        routine = routine.strip() or name
    if callable(routine):
        if a.get("script_name") or a.get("usrsub_dll_name"):
            raise ctx.error("give a Python function or a script/library, not both",
                            "usrsub_fnc_name")
        return UserSub(name, routine, par)
    if a.get("usrsub_dll_name") is not None:
        if a.get("script_name") is not None or a.get("interpreter") is not None:
            raise ctx.error("give a C library (usrsub_dll_name) or a Python script "
                            "(script_name, interpreter), not both", "usrsub_dll_name")
        path = find_file(ctx, a["usrsub_dll_name"], model.source.file, "usrsub_dll_name")
        _check_library(ctx, path, routine)
        return UserSub(name, routine, par, library=path, attribute="usrsub_dll_name")
    if a.get("script_name") is None:
        raise ctx.error(f"type=\"USERSUB\" needs the routine: script_name (a Python script "
                        f"defining {routine}) or, in a Python deck, ROUTINE= a function",
                        "script_name")
    path = find_file(ctx, a["script_name"], model.source.file, "script_name")
    _check_script(ctx, path, routine, args)
    return UserSub(name, routine, par, script=path, attribute="script_name")


def expression_or_routine(model, ctx, a, routine):
    """(tree, text, usersub) of an element given by `expr` or by its user subroutine
    (`routine`, named in the error when neither is given); the tree is None until the routine
    is traced or bound, when the model is first compiled."""
    sub = from_attributes(model, ctx, a)
    if sub is not None:
        return None, sub.describe(), sub
    if a.get("expr") is None:
        raise ctx.error(f"give expr, or a user subroutine ({routine}: script_name, "
                        "usrsub_dll_name, or ROUTINE= in a Python deck)", "expr")
    tree, text = a["expr"]
    if tree[0] == "user":
        typed = " type=\"USERSUB\" and" if "type" in a else ""
        raise ctx.error(f"USER(...) calls a user subroutine: give{typed} the routine "
                        "(script_name, usrsub_dll_name, or ROUTINE= in a Python deck)", "expr")
    return tree, text, None


def no_routine(ctx, key):
    """The DeckError of USER(...) in attribute `key` of an element that names no routine, in
    the deck's words: a Python or Adams statement's keywords, else XML's."""
    if ctx.named(key) != key:
        routine = ctx.names.get("usrsub_fnc_name", "ROUTINE")
        return ctx.error(f"USER(...) calls a user subroutine: give {routine}= the routine", key)
    return ctx.error("USER(...) calls a user subroutine: give type=\"USERSUB\" and the "
                     "routine (script_name, or ROUTINE= in a Python deck)", key)


def find_file(ctx, given, deck_file, attribute):
    """A script's or library's path: an absolute one as given; a relative one in the deck's
    folder (as MotionSolve looks beside the XML file), then in the current directory (the
    only folder of a deck given as text), then in the folders of PYSOLVER_USERSUB_DIR."""
    candidates = [given]
    if not os.path.isabs(given):
        candidates = [os.path.abspath(given)]
        if deck_file and not deck_file.startswith("<"):
            folder = os.path.dirname(os.path.abspath(deck_file))
            candidates.insert(0, os.path.join(folder, given))
        candidates += [os.path.join(d, given) for d in settings.usersub_dirs()]
        candidates = list(dict.fromkeys(candidates))     # the deck's folder may be the cwd
    for path in candidates:
        if os.path.isfile(path):
            return os.path.abspath(path)
    what = "script" if attribute == "script_name" else "library"
    raise ctx.error(f"{what} {given!r} not found (looked in: {', '.join(candidates)})",
                    attribute)


def _check_library(ctx, path, routine):
    """The library exports `routine` (its symbol table read, the library not loaded)."""
    try:
        names = elfsyms.exported_functions(path)
    except OSError as err:
        raise ctx.error(f"cannot read library {path}: {err.strerror}", "usrsub_dll_name") \
            from None
    except elfsyms.NotElf as err:
        if sys.platform.startswith("linux"):
            raise ctx.error(f"{path} is not a shared library: {err}", "usrsub_dll_name") \
                from None
        return                          # another object format: checked when it is loaded
    if routine not in names:
        shown = ", ".join(sorted(names)[:12]) + (", ..." if len(names) > 12 else "")
        raise ctx.error(f"library {path} exports no function {routine} (it exports: "
                        f"{shown or 'none'})", "usrsub_fnc_name")


def _check_script(ctx, path, routine, args):
    """The script parses and defines `routine` taking the conventional arguments (read, not
    run)."""
    try:
        with open(path, encoding="utf-8") as fh:
            tree = ast.parse(fh.read(), path)
    except (OSError, UnicodeDecodeError, SyntaxError, ValueError) as err:
        raise ctx.error(f"cannot read script {path}: {err}", "script_name") from None
    defs = [n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == routine]
    if not defs:
        raise ctx.error(f"script {path} defines no function {routine}", "usrsub_fnc_name")
    fn = defs[-1].args
    npos = len(fn.posonlyargs) + len(fn.args)
    if fn.vararg is None and npos != len(args):
        raise ctx.error(f"{routine} in {path} (line {defs[-1].lineno}) takes {npos} arguments; "
                        f"expected {len(args)}: {', '.join(args)}", "usrsub_fnc_name")


# ---------------------------------------------------------------------------------------------
# compile time: trace every Python routine into the element's expression

#: The Model tables of the elements a user subroutine may define, by kind.
TABLES = {e.kind: e.table for e in catalogue.ELEMENTS if e.usersub}


def elements(model):
    """(kind, element) of every element defined by a user subroutine."""
    for kind, name in TABLES.items():
        for el in list(getattr(model, name).values()):
            if el.usersub is not None:
                yield kind, el


def set_trees(model, kind, el, trees):
    """Put an element's expression trees from its user subroutine in the compiled scene
    `model` (a Model's working copy: the loaded Model itself never changes)."""
    if kind == "request":
        texts = [f"{el.usersub.label} channel {k + 1}" for k in range(8)]
        new = dataclasses.replace(el, exprs=list(trees), texts=texts)
    else:
        new = dataclasses.replace(el, expr=trees[0])
    getattr(model, TABLES[kind])[el.id] = new


def resolve(model):
    """Trace the model's Python user subroutines into expression trees (once; idempotent).

    Raises
    ------
    DeckError
        A routine cannot be loaded, raises, returns something that is not a number, calls
        py_sysfnc with an unknown function or ids, or cannot be traced (the message says
        where and why).
    """
    done = []
    for kind, el in elements(model):
        if (el.exprs[0] if kind == "request" else el.expr) is not None or el.usersub.library \
                or el.usersub.untraced:
            continue
        ctx = model._where[(kind, el.id)]
        ctx.id = el.id
        trees = _trace(ctx, el.usersub, el.id, model)
        if trees is None:
            continue                    # called from the kernel instead (build.usercalls)
        set_trees(model, kind, el, trees)
        done.append((kind, el))
        model.usersub_paths[f"{ctx.tag} {el.id}"] = (
            f"{el.usersub.describe()}: traced into the kernel: "
            + "; ".join(ex.unparse(t) for t in trees))
    if done:
        from .references import check_references
        check_references(model)


def python_routine(ctx, sub, model, traced=False):
    """The routine's Python function; for tracing (traced=True) with the math module replaced.
    A script is run once per model, when the model is first compiled."""
    if callable(sub.routine):
        fn = sub.routine
        if traced and isinstance(fn, types.FunctionType):
            fn = types.FunctionType(fn.__code__, tracelib.shim_globals(fn.__globals__),
                                    fn.__name__, fn.__defaults__, fn.__closure__)
        return fn
    scripts = model._scripts
    if sub.script not in scripts:
        namespace = {"__name__": "__pysolver_usersub__", "__file__": sub.script,
                     "py_sysfnc": tracer.py_sysfnc, "py_sysary": tracer.py_sysary,
                     "py_errmes": tracer.py_errmes, "py_syspar": tracer.py_syspar,
                     "__builtins__": _builtins()}
        try:
            with open(sub.script, encoding="utf-8") as fh:
                code = compile(fh.read(), sub.script, "exec")
            exec(code, namespace)
        except (Exception, SystemExit) as err:  # the script's own error, at its line
            raise ctx.error(f"script {sub.script} failed to run: {_where(err, sub.script)}",
                            "script_name") from None
        scripts[sub.script] = namespace
    fn = scripts[sub.script].get(sub.routine)
    if not callable(fn):
        raise ctx.error(f"script {sub.script} defines no function {sub.routine}",
                        "usrsub_fnc_name")
    return fn


def _builtins():
    """Builtins whose import of math gives the tracing stand-in."""
    import builtins
    table = dict(vars(builtins))
    real_import = builtins.__import__

    def imp(name, globals=None, locals=None, fromlist=(), level=0):
        if name == "math" and level == 0:
            return tracelib.SHIM
        return real_import(name, globals, locals, fromlist, level)
    table["__import__"] = imp
    return table


def _on_numbers(call):
    """What `call` of the routine raises on numbers (time and every value py_sysfnc and
    py_sysary read 0, as in the kernel's iflag call), or None: tells a routine's own error from
    one a library raised on a traced value (a routine that raises at every state raises on
    numbers too, at the same line)."""
    prev = tracer.enter_live(lambda fnc, ids: [0.0, 0], lambda fnc, ids, partials: 0)
    try:
        call()
    except (Exception, SystemExit) as err:
        return err
    finally:
        tracer.leave_live(prev)
    return None


def _line(err, file):
    """The deepest line of `file` in err's traceback, or None."""
    lines = [f.lineno for f in traceback.extract_tb(err.__traceback__)
             if file is None or os.path.abspath(f.filename) == os.path.abspath(file)]
    return lines[-1] if lines else None


def _where(err, file):
    """'Type: message (file line N)' with the deepest line of `file` in the traceback (for a
    branch that raised, the traceback of what it raised)."""
    cause = err.__cause__ if isinstance(err, tracer.Untraceable) else None
    line = (_line(cause, file) if cause is not None else None) or _line(err, file)
    text = f"{type(err).__name__}: {err}" if not isinstance(err, (tracer.Untraceable,
                                                                   tracer.SysfncError,
                                                                   tracer.RoutineError)) \
        else str(err)
    return text + (f" (line {line})" if line else "")


def _trace(ctx, sub, id, model):
    """Call the routine as MotionSolve does (iflag pass, then an evaluation) on traced values,
    along every path of its state-dependent branches; returns the trees of its values, or
    None when it cannot be traced (sub.untraced says why: it will be called from the kernel).
    A routine that may keep state between calls (:mod:`.statecheck`) is not traced."""
    why = statecheck.keeps_state(python_routine(ctx, sub, model))
    if why:
        sub.untraced = f"not traced: it may keep state between calls: {why}"
        return None
    fn = python_routine(ctx, sub, model, traced=True)
    _, args, nvalues = CONVENTIONS[ctx.tag]
    file = sub.script or getattr(getattr(fn, "__code__", None), "co_filename", None)
    par = list(sub.par)

    def call(time, iflag):
        values = {"id": id, "time": time, "par": list(par), "npar": len(par), "dflag": 0,
                  "iord": 0, "iflag": iflag}
        return fn(*[values[k] for k in args])

    def run(iflag):
        with tracer.active():
            out = call(tracer.Sym(("name", "TIME", 0)), iflag)
        return _value_trees(ctx, sub, out, nvalues) if iflag == 0 else None

    iflag = 1
    try:
        tracer.explore(lambda: run(1))
        iflag = 0
        leaves = tracer.explore(lambda: run(0))
        trees = [_join_channel(leaves, k) for k in range(nvalues)]
    except tracer.Untraceable as err:
        sub.untraced = f"not traced: {_where(err, file)}"
        return None
    except (tracer.SysfncError, tracer.RoutineError) as err:
        raise ctx.error(f"{sub.label}: {_where(err, file)}", sub.attribute) from None
    except DeckError:
        raise
    except (Exception, SystemExit) as err:  # on no branch: the routine's error, or the tracer's
        own = _on_numbers(lambda: call(0.0, iflag))
        if own is None or type(own) is not type(err) or _line(own, file) != _line(err, file):
            sub.untraced = (f"not traced: {_where(err, file)}, raised on traced values and not "
                            "on numbers (time and every value it reads 0): a function the "
                            "tracer cannot follow")
            return None
        raise ctx.error(f"{sub.label} raised {_where(own, file)}", sub.attribute) from None
    deepest = max((ex.depth(t) for t in trees if t is not None), default=0)
    if deepest > ex.MAX_DEPTH:
        sub.untraced = (f"not traced: its expression nests {deepest} levels deep, more than "
                        f"the {ex.MAX_DEPTH} a traced expression may")
        return None
    try:
        for t in trees:
            if t is not None:
                ex._check(t)
    except ExpressionError as err:   # pragma: no cover - the tracer builds checked nodes
        raise ctx.error(f"{sub.label}: {err}", sub.attribute) from None
    return trees


def _join_channel(leaves, k):
    """Channel k over every path; a channel some paths leave out is 0 there."""
    values = [r[k] for _, _, r in leaves]
    if all(v is None for v in values):
        return None
    return tracer.join([(d, c, ("num", 0.0) if v is None else v)
                        for (d, c, _), v in zip(leaves, values)])


def _value_trees(ctx, sub, values, nvalues):
    """The trees of one return value: one per channel (None: a REQSUB channel left out)."""
    if nvalues == 1:
        values = [values]
    elif isinstance(values, np.ndarray) and values.ndim == 1:
        values = list(values)           # a NumPy REQSUB's array, as the kernel's call takes it
    if not isinstance(values, (list, tuple)) or len(values) > nvalues:
        raise ctx.error(f"{sub.label} must return a list of up to {nvalues} values, got "
                        f"{values!r}", sub.attribute)
    trees = []
    for v in list(values) + [None] * (nvalues - len(values)):
        if v is None and nvalues > 1:
            trees.append(None)
            continue
        try:
            trees.append(tracer.tree_of(v))
        except tracer.Untraceable as err:
            raise ctx.error(f"{sub.label} returned {v!r}: {err}", sub.attribute) from None
    return trees
