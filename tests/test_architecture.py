"""The package's layout stays as docs/architecture.md draws it: imports point from later stages
to earlier ones only, there is no import circle, one module touches the compiled extension, and
no module grows past ~400 lines without saying why."""
import ast
import pathlib

import pytest

import pysolver

PKG = pathlib.Path(pysolver.__file__).resolve().parent

#: Stages in the order of the data flow, as import ranks: a module may import its own stage and
#: earlier ones. Records and shared vocabulary (options, errors, results, rotations, catalogue)
#: come first; ``Model.run`` reaches the solvers through an import inside the call (the facade).
#: The viewer and plotting rank with results (Result.animate and Result.plot call them).
RANK = {"_version": 0, "headers": 0, "errors": 0, "options": 0, "rotations": 0, "naming": 0, "results": 4,
        "catalogue": 0, "settings": 0, "imports": 0, "records": 1, "model": 1,
        "deck": 2, "build": 3, "_kernel": 3, "solve": 4, "viewer": 4, "plotting": 4, "batch": 5,
        "cli": 5,
        "msolve": 5, "modeling": 5, "convert": 5,
        "__init__": 5,
        "__main__": 5, "_build_ffi": 5}


def _modules():
    for path in sorted(PKG.rglob("*.py")):
        rel = path.relative_to(PKG).with_suffix("")
        yield ".".join(rel.parts), path


def _module_level_imports(name, path):
    """Internal modules imported when the module is imported: imports inside functions run at
    call time and TYPE_CHECKING blocks never run, so neither counts."""
    tree = ast.parse(path.read_text())
    package = name.split(".")[:-1]
    found = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)) or \
                (isinstance(node, ast.If) and "TYPE_CHECKING" in ast.dump(node.test)):
            continue
        for sub in ast.walk(node):
            if isinstance(sub, ast.ImportFrom) and sub.level:
                base = package[:len(package) - (sub.level - 1)] if sub.level > 1 else package
                target = base + (sub.module.split(".") if sub.module else [])
                names = [target + [a.name] for a in sub.names] if not sub.module else [target]
                found.update(".".join(t) for t in names)
            elif isinstance(sub, ast.ImportFrom) and sub.module and \
                    sub.module.startswith("pysolver"):
                found.add(sub.module[len("pysolver."):])
    return {f for f in found if f}


def _all_imports(name, path):
    """Internal modules a module imports anywhere, inside functions too (they run later, but
    still point from one stage to another)."""
    tree = ast.parse(path.read_text())
    package = name.split(".")[:-1]
    found = set()
    checking = [n for n in ast.walk(tree)          # TYPE_CHECKING blocks never run
                if isinstance(n, ast.If) and "TYPE_CHECKING" in ast.dump(n.test)]
    skip = {id(sub) for n in checking for sub in ast.walk(n)}
    for sub in ast.walk(tree):
        if id(sub) in skip:
            continue
        if isinstance(sub, ast.ImportFrom) and sub.level:
            base = package[:len(package) - (sub.level - 1)] if sub.level > 1 else package
            target = base + (sub.module.split(".") if sub.module else [])
            names = [target + [a.name] for a in sub.names] if not sub.module else [target]
            found.update(".".join(t) for t in names)
        elif isinstance(sub, ast.ImportFrom) and sub.module and sub.module.startswith("pysolver"):
            found.add(sub.module[len("pysolver."):])
    # names imported from the package itself (from .. import load) are the package's __init__
    return {f if f.split(".")[0] in RANK else "__init__" for f in found if f}


#: Imports inside functions that point to a later stage, and why. Model is the facade onto the
#: later stages: compile and check import them when called, and unpickling loads the deck.
LATER_STAGE_CALLS = {"model": {"deck.loader", "solve.compiled", "solve.outputs"}}


def _stage(module):
    return RANK[module.split(".")[0]]


def test_imports_point_to_earlier_stages_only():
    for name, path in _modules():
        for target in _module_level_imports(name, path):
            assert _stage(target) <= _stage(name), f"{name} imports {target}, a later stage"


def test_imports_inside_functions_point_to_earlier_stages_too():
    for name, path in _modules():
        for target in _all_imports(name, path) - LATER_STAGE_CALLS.get(name, set()):
            assert _stage(target) <= _stage(name), \
                f"{name} imports {target}, a later stage, inside a function"


@pytest.mark.parametrize("anywhere", [False, True])
def test_no_import_circle(anywhere):
    """No circle among module-level imports, nor among all imports but the facade's."""
    graph = {}
    known = {name for name, _ in _modules()}
    for name, path in _modules():
        graph[name] = set()
        targets = _all_imports(name, path) - LATER_STAGE_CALLS.get(name, set()) if anywhere \
            else _module_level_imports(name, path)
        for target in targets:
            # "from . import x" may name a module or a package's __init__
            for cand in (target, target + ".__init__"):
                if cand in known:
                    graph[name].add(cand)
    state = {}

    def visit(node, stack):
        state[node] = "open"
        for nxt in graph.get(node, ()):
            if nxt == node.rsplit(".", 1)[0] + ".__init__":
                continue        # a module importing its own package's __init__ is not a cycle
            assert state.get(nxt) != "open", " -> ".join(stack + [node, nxt])
            if nxt not in state:
                visit(nxt, stack + [node])
        state[node] = "done"

    for name in graph:
        if name not in state:
            visit(name, [])


def test_one_module_touches_the_extension():
    users = [name for name, path in _modules() if "_kernel" in
             {t.split(".")[-1] for t in _module_level_imports(name, path)}]
    assert users == ["build.bindings"]


def test_modules_stay_small_or_say_why():
    for name, path in _modules():
        text = path.read_text()
        if text.count("\n") > 420:
            assert "Longer than" in text[:1500], f"{name}: {text.count(chr(10))} lines, no reason"
