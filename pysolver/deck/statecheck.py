"""Whether a Python user subroutine may keep state between calls, read from its bytecode.

A traced routine is called once per path of its state-dependent branches when the model is
compiled, and never again: state it keeps between calls (a latch, a running maximum, a call
counter) would carry from one traced path into the next and freeze into a wrong expression
(trial 45). Such a routine is called from the kernel instead. :func:`keeps_state` errs on the
side of calling: it reports a routine, or a function of the deck's or the user's own code
that it calls, that

- assigns or deletes a global (``global x; x = ...``) or an enclosing function's variable
  (``nonlocal``), or sets or deletes an attribute of anything (``Latch.on = True``,
  ``self.n += 1``);
- reads a global, a closure cell or a module attribute holding something that can change
  between calls: a list, dict, set, bytearray, writeable NumPy array, an instance of a class
  with attributes, a class of the user's own (its attributes), a bound method of such an
  object, or a global that a function of the same module assigns (``global``);
- has a mutable default argument, is a bound method of an object with attributes, or is a
  callable object other than a plain function (its state cannot be seen);
- uses ``globals``, ``vars``, ``setattr``, ``delattr``, ``exec``, ``eval``, or the
  ``random``, ``numpy.random``, ``time`` or ``datetime`` modules, or imports a module of the
  user's own inside the call.

Numbers, strings, tuples of them, modules, library functions and classes (Python's, NumPy's,
SciPy's, pysolver's) are not state. What a routine reaches through its arguments (``par`` is a
fresh list at every call) is not seen; nor is state kept inside a C extension.
"""
import dis
import functools
import numbers
import os
import sys
import sysconfig
import types

import numpy as np

#: Library packages whose functions, classes and module attributes are not the user's state.
_LIBRARIES = frozenset(sys.stdlib_module_names) | {"numpy", "scipy", "pysolver"}
#: ... except these, whose functions keep or read state of their own.
_STATEFUL_MODULES = ("random", "numpy.random", "time", "datetime", "secrets")
_STATEFUL_BUILTINS = frozenset({"globals", "vars", "setattr", "delattr", "exec", "eval"})
_LOADS = frozenset({"LOAD_GLOBAL", "LOAD_NAME", "LOAD_DEREF", "LOAD_CLASSDEREF",
                    "LOAD_FROM_DICT_OR_DEREF"})
_ATTRS = frozenset({"LOAD_ATTR", "LOAD_METHOD"})
_LIBRARY_DIRS = tuple({os.path.realpath(p) + os.sep for k in ("stdlib", "platstdlib", "purelib",
                                                             "platlib")
                       if (p := sysconfig.get_paths().get(k))})
_IMMUTABLE_TYPE = 1 << 8                  # Py_TPFLAGS_IMMUTABLETYPE: a builtin or C type


def keeps_state(fn):
    """Why the routine `fn` may keep or read state that changes between calls, or None.

    Parameters
    ----------
    fn : callable
        The routine as the deck gives it (a function, a method, a callable object).

    Returns
    -------
    str or None
        A short reason ("assigns the global latched"), or None when its code provably keeps
        none by the rules of this module.
    """
    if isinstance(fn, types.MethodType):
        why = _mutable(fn.__self__)
        if why and not isinstance(fn.__self__, (type, types.ModuleType)):
            return f"it is a method of {why}"
        fn = fn.__func__
    if not isinstance(fn, types.FunctionType):
        return f"it is {_what(fn)}, not a plain function: its state cannot be seen"
    return _function(fn, set(), 0)


def _function(fn, seen, depth):
    """keeps_state of a plain function, and of the user's functions it calls (to depth 4)."""
    if fn.__code__ in seen or depth > 4:
        return None
    seen.add(fn.__code__)
    name = fn.__name__
    for default in list(fn.__defaults__ or ()) + list((fn.__kwdefaults__ or {}).values()):
        why = _mutable(default)
        if why:
            return f"{name} has a mutable default argument ({why})"
    cells = dict(zip(fn.__code__.co_freevars, fn.__closure__ or ()))
    assigned = _module_assigns(fn.__globals__)
    instructions = list(_instructions(fn.__code__))
    imported = ""
    for ins, _ in instructions:         # what it stores, then what it reads
        op, arg = ins.opname, ins.argval
        if op in ("STORE_GLOBAL", "DELETE_GLOBAL"):
            return f"{name} assigns the global {arg}"
        if op in ("STORE_DEREF", "DELETE_DEREF") and arg not in fn.__code__.co_cellvars:
            return f"{name} assigns the enclosing function's variable {arg} (nonlocal)"
        if op in ("STORE_ATTR", "DELETE_ATTR"):
            return f"{name} sets the attribute {arg} of an object"
        if op == "IMPORT_NAME" and not _library(arg):
            return f"{name} imports the module {arg}"
        if op in _ATTRS and arg == "__dict__":
            return f"{name} reads an object's __dict__"
        if op == "IMPORT_NAME":
            imported = arg
        if op == "IMPORT_FROM" and f"{imported}.{arg}" in _STATEFUL_MODULES:
            return f"{name} imports the module {imported}.{arg}"
    for ins, nxt in instructions:
        op, arg = ins.opname, ins.argval
        if op not in _LOADS:
            continue
        if arg in cells and op != "LOAD_GLOBAL":
            try:
                value = cells[arg].cell_contents
            except ValueError:          # an empty cell
                continue
            where = f"the enclosing function's variable {arg}"
        elif arg in fn.__globals__:
            value, where = fn.__globals__[arg], f"the global {arg}"
            if arg in assigned:
                return f"{name} reads {where}, which {assigned[arg]} assigns"
        elif op == "LOAD_DEREF":        # a cell of its own (a nested function's variable)
            continue
        else:
            builtins = fn.__globals__.get("__builtins__", {})
            builtins = builtins if isinstance(builtins, dict) else vars(builtins)
            if arg in _STATEFUL_BUILTINS and arg in builtins:
                return f"{name} calls {arg}"
            continue
        why = _value(value, where, nxt, seen, depth)
        if why:
            return f"{name} {why}"
    return None


def _value(value, where, nxt, seen, depth):
    """Why reading `value` (from `where`, with the attribute loads that follow it) is state."""
    attrs = []
    while isinstance(value, types.ModuleType):
        if value.__name__ in _STATEFUL_MODULES:
            return f"uses the module {value.__name__}, whose functions keep state"
        if _library(value.__name__) and not any(
                isinstance(getattr(value, a.argval, None), types.ModuleType) for a in nxt[:1]
                if a.opname in _ATTRS):
            # a library's function or constant; not its mutable data (sys.modules, os.environ)
            got = getattr(value, nxt[0].argval, None) if nxt and nxt[0].opname in _ATTRS \
                else None
            why = _mutable(got) if got is not None else None
            return f"reads {where}.{nxt[0].argval}, {why} that can change between calls" \
                if why else None
        if not nxt or nxt[0].opname not in _ATTRS:
            return None
        attrs.append(nxt[0].argval)
        value = getattr(value, nxt[0].argval, None)
        nxt = nxt[1:]
    if attrs:
        where = f"{where}.{'.'.join(attrs)}"
    if isinstance(value, types.FunctionType):
        if _library(value.__module__ or "") or _in_library(value.__code__.co_filename):
            return None
        why = _function(value, seen, depth + 1)
        return f"calls {value.__name__}: {why}" if why else None
    why = _mutable(value)
    return f"reads {where}, {why} that can change between calls" if why else None


def _mutable(value, depth=0):
    """What `value` is, when it is an object that can change (a list, an instance, ...)."""
    if value is None or isinstance(value, (numbers.Number, str, bytes, range, slice, np.generic,
                                           type(Ellipsis), types.ModuleType, np.ufunc)):
        return None
    if isinstance(value, (types.BuiltinFunctionType, types.MethodWrapperType)):
        # a C function: a module's (math.sqrt; random's and time's keep state) or a method
        # bound to an object (set().add, a hidden Random's random) that may change
        owner = getattr(value, "__self__", None)
        if owner is None or isinstance(owner, types.ModuleType):
            module = getattr(owner, "__name__", None) or value.__module__ or ""
            stateful = any(module == m or module.startswith(m + ".") or
                           module.lstrip("_") == m for m in _STATEFUL_MODULES)
            return f"a function of the module {module}" if stateful else None
        why = None if isinstance(owner, type) else _mutable(owner, depth + 1)
        return f"a method of {why}" if why else None
    if isinstance(value, functools.partial):
        return next((w for w in (_mutable(v, depth + 1) for v in
                                 [value.func, *value.args, *value.keywords.values()]) if w),
                    None) if depth < 3 else "a functools.partial"
    if isinstance(value, (tuple, frozenset)):
        return next((w for w in (_mutable(v, depth + 1) for v in list(value)[:50]) if w), None) \
            if depth < 3 else None
    if isinstance(value, types.FunctionType):
        # attributes set on a function (f.calls = ...) are state; so is a cached one
        return "a function with attributes" if value.__dict__ and set(value.__dict__) - {
            "__wrapped__"} or hasattr(value, "cache_info") else None
    if isinstance(value, types.MethodType):
        owner = value.__self__
        return None if isinstance(owner, (types.ModuleType, type)) else \
            (f"a method of {_mutable(owner)}" if _mutable(owner) else None)
    if isinstance(value, type):
        if value.__flags__ & _IMMUTABLE_TYPE or _library(value.__module__):
            return None
        return f"the class {value.__name__} (its attributes)"
    if isinstance(value, np.ndarray):
        return "a NumPy array" if value.flags.writeable else None
    if type(value).__module__.split(".")[0] == "pysolver":
        return None                     # the tracer's math shim
    if callable(value) and _library(type(value).__module__):
        # a library's function object (np.sum's dispatcher): state only in a cache or in
        # attributes that can change
        if hasattr(value, "cache_info"):
            return f"a cached function ({type(value).__name__})"
        if depth >= 3:
            return None
        return next((f"{type(value).__name__} holding {w}" for w in
                     (_mutable(v, depth + 1) for v in vars_of(value).values()) if w), None)
    return _what(value)


def vars_of(value):
    """The attributes an object holds in its __dict__ (none when it has no __dict__), its
    dunder ones (__doc__, __annotations__, __wrapped__) left out."""
    try:
        return {k: v for k, v in vars(value).items()
                if not (k.startswith("__") and k.endswith("__"))}
    except TypeError:
        return {}


def _what(value):
    kind = type(value).__name__
    if isinstance(value, (list, dict, set, bytearray)):
        return f"a {kind}"
    return f"{'an' if kind[:1].lower() in 'aeiou' else 'a'} {kind} object"


def _library(module):
    top = (module or "").split(".")[0]
    return top in _LIBRARIES and module not in _STATEFUL_MODULES


def _in_library(filename):
    return os.path.realpath(filename).startswith(_LIBRARY_DIRS)


def _instructions(code):
    """(instruction, the instructions after it) of a code object and the code objects nested
    in it (comprehensions, lambdas, inner functions)."""
    ins = list(dis.get_instructions(code))
    for i, one in enumerate(ins):
        yield one, ins[i + 1:i + 4]
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            yield from _instructions(const)


def _module_assigns(namespace):
    """{global name: the function of `namespace` that assigns it with ``global``}."""
    out = {}
    for value in list(namespace.values()):
        if isinstance(value, types.FunctionType) and value.__globals__ is namespace:
            for ins, _ in _instructions(value.__code__):
                if ins.opname in ("STORE_GLOBAL", "DELETE_GLOBAL"):
                    out.setdefault(ins.argval, value.__name__)
    return out
