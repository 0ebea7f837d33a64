"""The generated kernel's disk cache and compiler never fail a run (pysolver.build.codegen.cache):
an unusable cache or compiler, a compile too costly or too slow, a generated-code compile error
and a cache entry that is not this scene's library each run the tapes (or rebuild the entry)
with one line in res.log saying why, and the same answer."""
import hashlib
import json
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import time

import numpy as np
import pytest

import pysolver
from pysolver.build import codegen
from pysolver.build.codegen import cache as kcache
from pysolver.build.codegen import emit

from helpers import ROOT

DECK = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="2" body_id="2" pos_z="1"/>
  <Body_Point id="2" cg_id="2" mass="{mass}"/><Force_Gravity grav_z="-9.81"/>
  <Force_Penalty id="1" expr="0.5 - DZ(2) + 0.01 * HAVSIN(TIME, 0, 0, 0.3, 1)" unilateral="TRUE"
                 penalty="1e3" penalty1="5"/>
  <Post_Request id="1" expr1="DZ(2)" expr2="PFORCE(1)" name1="z" name2="f"/>
  <Param_Transient integr_tol="1e-6"/></Model>
  <Simulate analysis_type="Transient" end_time="0.5" print_interval="0.1"/></MotionSolve>"""

GCC = shutil.which("gcc") or shutil.which("cc")
needs_gcc = pytest.mark.skipif(GCC is None, reason="no C compiler")


def sin_sum_deck(n):
    """Issue 22 item 2: a Force_Penalty whose expression is n SIN terms of the state summed as
    a balanced tree."""
    def tree(terms):
        if len(terms) == 1:
            return terms[0]
        h = len(terms) // 2
        return f"({tree(terms[:h])}+{tree(terms[h:])})"
    expr = tree([f"SIN(DX(10)+{k}*0.001)" for k in range(n)])
    return f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="10" body_id="2" pos_y="3"/>
  <Body_Point id="2" cg_id="10" mass="1.0"/><Force_Gravity grav_y="-9.81"/>
  <Force_Penalty id="1" expr="{expr}" unilateral="TRUE" penalty="1e3" penalty1="5"/>
  <Param_Transient integr_tol="1e-6"/></Model>
  <Simulate analysis_type="Transient" end_time="0.5" print_interval="0.1"/></MotionSolve>"""


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty kernel cache for one test, and the default compile time limit."""
    monkeypatch.setenv("PYSOLVER_CACHE_DIR", str(tmp_path / "kernels"))
    monkeypatch.delenv("PYSOLVER_COMPILE_TIMEOUT", raising=False)
    monkeypatch.delenv("CC", raising=False)
    return tmp_path / "kernels"


@pytest.fixture(scope="module")
def tapes_answer():
    return pysolver.loads(DECK.format(mass=1.0)).run(kernel="tapes")


def _kernel_lines(res):
    return [line for line in res.log if line.startswith("kernel:")]


def _on_tapes(res, tapes_answer, *words):
    """res ran on the tapes, succeeded with tapes_answer's numbers and logged one kernel line
    holding every one of words; return that line."""
    assert res.success and res.meta["kernel"] == "tapes", (res.meta, res.log)
    lines = _kernel_lines(res)
    assert len(lines) == 1, res.log
    for word in words:
        assert word in lines[0], lines[0]
    assert np.array_equal(res.y, tapes_answer.y)
    return lines[0]


def _script(folder, name, text):
    path = pathlib.Path(folder) / name
    path.write_text("#!/bin/sh\n" + text)
    path.chmod(0o755)
    return path


def _run_elsewhere(env_extra, mass=1.0, timeout=300):
    """Load and run DECK in a fresh process (a bad library that reached dlopen would kill the
    test session, a FIFO hang it); return its kernel info, log, success and last state."""
    script = (
        "import json, pysolver\n"
        f"m = pysolver.loads({DECK.format(mass=mass)!r})\n"
        "res = m.run()\n"
        "info = {k: v for k, v in m.compile().kernel.codegen.items() if isinstance(v, (str, bool, int,"
        " float))}\n"
        "print(json.dumps({'info': info, 'log': res.log, 'success': bool(res.success),"
        " 'y': res.y[-1].tolist()}))\n")
    env = dict(os.environ, PYTHONPATH=str(ROOT), **env_extra)
    done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                          text=True, timeout=timeout)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def _build_entry(cache_dir, mass=1.0):
    """Build DECK's library into cache_dir in another process; return (library, stamp)."""
    got = _run_elsewhere({"PYSOLVER_CACHE_DIR": str(cache_dir)}, mass)
    assert got["info"]["kernel"] == "generated", got
    lib = pathlib.Path(got["info"]["path"])
    return lib, lib.with_suffix(".sha256")


def _restamp(lib, stamp):
    stamp.write_text(hashlib.sha256(lib.read_bytes()).hexdigest())


# --- issue 22 item 1: an unusable cache or a broken compiler runs the tapes ---------------------

@pytest.mark.parametrize("where", ["file", "under_file", "read_only"])
def test_unusable_cache_folder_runs_the_tapes_with_one_log_line(where, tmp_path, monkeypatch,
                                                                 tapes_answer):
    monkeypatch.delenv("CC", raising=False)
    blocker = tmp_path / "blocker"
    blocker.write_text("not a folder")
    folder = {"file": blocker, "under_file": blocker / "kernels",
              "read_only": tmp_path / "ro"}[where]
    if where == "read_only":
        folder.mkdir()
        folder.chmod(0o555)
        try:
            (folder / "probe").write_text("")
            writable = True                        # root: permissions do not stop it
        except OSError:
            writable = False
        if writable:
            (folder / "probe").unlink()

            def refuse(*args, **kwargs):
                raise PermissionError(13, "Permission denied", str(folder))
            monkeypatch.setattr(kcache.tempfile, "mkdtemp", refuse)
    monkeypatch.setenv("PYSOLVER_CACHE_DIR", str(folder))
    try:
        res = pysolver.loads(DECK.format(mass=1.0)).run()
    finally:
        if where == "read_only":
            folder.chmod(0o755)
    line = _on_tapes(res, tapes_answer, "the kernel cache", str(folder), "is unusable")
    reason = {"file": "exists", "under_file": "Not a directory",
              "read_only": "Permission denied"}[where]
    assert reason in line, line


@needs_gcc
def test_read_only_cache_with_an_entry_is_used(cache, tmp_path, monkeypatch):
    """A cache that cannot be written still serves the entries it has."""
    lib, _ = _build_entry(cache)
    def refuse(*args, **kwargs):
        raise AssertionError("a cache hit wrote to the cache")
    monkeypatch.setattr(kcache.tempfile, "mkdtemp", refuse)
    model = pysolver.loads(DECK.format(mass=1.0))
    info = model.compile().kernel.codegen
    assert info["kernel"] == "generated" and info["cached"] and info["path"] == str(lib)


@needs_gcc
def test_a_stamp_of_non_utf8_bytes_is_rebuilt_not_raised(cache):
    lib, stamp = _build_entry(cache)
    stamp.write_bytes(b"\xff\xfe\x80 not a digest \xc3\x28")
    model = pysolver.loads(DECK.format(mass=1.0))
    info = model.compile().kernel.codegen
    assert info["kernel"] == "generated" and not info["cached"], info
    assert "its stamp is not a digest (non-ASCII bytes)" in info["rebuilt"]
    assert model.run().success
    assert pysolver.loads(DECK.format(mass=1.0)).compile().kernel.codegen["cached"]


@pytest.mark.parametrize("cc, words", [
    ('gcc -O1 "-DX=1', ["cannot be parsed as a command", "No closing quotation"]),
    ("true", ["'true' exited 0 but wrote no library"]),
    ("   ", ["names no command"]),
])
def test_a_broken_compiler_runs_the_tapes_with_one_log_line(cc, words, cache, monkeypatch,
                                                             tapes_answer):
    monkeypatch.setenv("CC", cc)
    res = pysolver.loads(DECK.format(mass=1.0)).run()
    _on_tapes(res, tapes_answer, *words)
    assert not list(cache.glob("*.so")) and not list(cache.glob(".build-*"))


def _alive(pid):
    """Whether process pid exists and is not a zombie."""
    try:
        status = pathlib.Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    return not re.search(r"^State:\s+Z", status, re.M)


@pytest.mark.skipif(not pathlib.Path("/proc/self/status").exists(), reason="needs /proc")
def test_a_hanging_compiler_is_killed_with_its_group_and_remembered(cache, tmp_path,
                                                                    monkeypatch, tapes_answer):
    """A compiler that answers --version but never finishes a compile (here it waits on a child
    holding its output open) is killed with the whole process group past the time limit, its
    build folder removed; the next load does not wait for it again."""
    pids = tmp_path / "pids"
    cc = _script(tmp_path, "hang-cc", f"""
if [ "$1" = --version ]; then echo hang-cc 1.0; exit 0; fi
sleep 600 &
echo $$ $! > {shlex.quote(str(pids))}
wait
""")
    monkeypatch.setenv("CC", str(cc))
    monkeypatch.setenv("PYSOLVER_COMPILE_TIMEOUT", "2")
    t0 = time.perf_counter()
    res = pysolver.loads(DECK.format(mass=1.0)).run()
    assert time.perf_counter() - t0 < 60
    _on_tapes(res, tapes_answer, "did not compile", "within 2 s", "killed")
    for pid in map(int, pids.read_text().split()):
        for _ in range(50):
            if not _alive(pid):
                break
            time.sleep(0.1)
        assert not _alive(pid), f"process {pid} of the compile still runs"
    assert not list(cache.glob(".build-*")) and not list(cache.glob("*.so"))
    t0 = time.perf_counter()
    again = pysolver.loads(DECK.format(mass=1.0)).run()
    assert time.perf_counter() - t0 < 2.0
    _on_tapes(again, tapes_answer, "within 2 s in an earlier run", "PYSOLVER_COMPILE_TIMEOUT")


# --- issue 22 item 2: the compile cost is capped ----------------------------------------------

def test_a_3000_term_sin_sum_runs_the_tapes_without_compiling(cache, monkeypatch):
    """The deck of the issue (gcc: 45-830 s) is refused by the estimated compile cost, before
    any compile, in well under a second of generation."""
    text = sin_sum_deck(3000)
    assert len(text) > 70_000
    t0 = time.perf_counter()
    res = pysolver.loads(text).run()
    assert time.perf_counter() - t0 < 30
    assert res.success and res.meta["kernel"] == "tapes"
    (line,) = _kernel_lines(res)
    assert "too large to compile in bounded time" in line and "codegen.COMPILE_LIMIT 30 s" in line
    seconds = float(re.search(r"about (\d+) s of gcc", line).group(1))
    assert seconds > codegen.COMPILE_LIMIT
    assert not cache.exists() or not list(cache.iterdir())
    ref = pysolver.loads(text).run(kernel="tapes")
    assert np.array_equal(res.y, ref.y)


def test_the_compile_cost_grows_with_live_values_not_only_size():
    """The cost of one function of many values live at once (the SIN sum's Jacobian entry)
    outgrows its size: doubling the terms doubles the C but about quadruples the cost, which
    bounds gcc's time (quadratic there), unlike the graph's node count (LIMIT)."""
    small, large = (codegen.source(pysolver.loads(sin_sum_deck(n)).compile("tapes").kernel,
                                   codegen.LIMIT) for n in (750, 1500))
    assert 1.8 < len(large) / len(small) < 2.2
    assert codegen.compile_cost(large) / codegen.compile_cost(small) > 3.0
    kernel = pysolver.load(ROOT / "decks" / "spinning_top.xml").compile("tapes").kernel
    assert codegen.compile_cost(codegen.source(kernel)) < 2.0


@needs_gcc
@pytest.mark.skipif(not pathlib.Path("/proc").is_dir(), reason="needs /proc")
def test_a_compile_past_the_time_limit_is_killed_and_its_folder_removed(cache, monkeypatch):
    """A real gcc past the limit: the driver and cc1 are killed (no process still reads the
    build folder), the folder is removed, and a build folder a killed process left long ago is
    swept."""
    monkeypatch.setattr(codegen, "COMPILE_LIMIT", float("inf"))
    monkeypatch.setenv("PYSOLVER_COMPILE_TIMEOUT", "1")
    monkeypatch.setenv("CC", GCC)
    cache.mkdir(parents=True)
    stale = cache / ".build-stale"
    stale.mkdir()
    (stale / "kernel.c").write_text("/* left by a killed process */")
    old = time.time() - 2 * 3600
    os.utime(stale, (old, old))
    res = pysolver.loads(sin_sum_deck(1500)).run()
    assert res.success and res.meta["kernel"] == "tapes"
    (line,) = _kernel_lines(res)
    assert "did not compile" in line and "within 1 s" in line, line
    assert not list(cache.glob(".build-*"))
    time.sleep(0.2)
    for cmdline in pathlib.Path("/proc").glob("[0-9]*/cmdline"):
        try:
            text = cmdline.read_bytes()
        except OSError:
            continue
        assert str(cache).encode() not in text, text


# --- issue 22 item 3: an entry is loaded only if it is this scene's library -------------------

@needs_gcc
def test_a_restamped_truncated_library_is_rebuilt_not_loaded(cache):
    lib, stamp = _build_entry(cache)
    data = lib.read_bytes()
    os.remove(lib)
    lib.write_bytes(data[:len(data) // 2])
    _restamp(lib, stamp)
    got = _run_elsewhere({"PYSOLVER_CACHE_DIR": str(cache)})
    assert got["success"] and got["info"]["kernel"] == "generated", got
    assert "its library is truncated" in got["info"]["rebuilt"], got["info"]
    assert lib.stat().st_size > len(data) // 2
    assert pysolver.loads(DECK.format(mass=1.0)).compile().kernel.codegen["cached"]


@needs_gcc
def test_another_scenes_library_stamped_under_this_key_is_rebuilt(cache, tapes_answer):
    """A valid library of another scene (another deck's) restamped under this deck's key is
    refused by its scene record, rebuilt, and the run gives this deck's numbers."""
    other = pysolver.loads(sin_sum_deck(2)).compile().kernel.codegen
    assert other["kernel"] == "generated"
    lib, stamp = _build_entry(cache)
    os.remove(lib)
    shutil.copyfile(other["path"], lib)
    _restamp(lib, stamp)
    got = _run_elsewhere({"PYSOLVER_CACHE_DIR": str(cache)})
    assert got["success"] and got["info"]["kernel"] == "generated", got
    assert "was generated for another scene (its scene record differs)" in \
        got["info"]["rebuilt"], got["info"]
    assert np.allclose(got["y"], tapes_answer.y[-1], rtol=0, atol=1e-7)


@needs_gcc
@pytest.mark.parametrize("which", ["library", "stamp"])
def test_a_fifo_in_place_of_the_library_is_rebuilt_without_hanging(which, cache):
    lib, stamp = _build_entry(cache)
    fifo = lib if which == "library" else stamp
    os.remove(fifo)
    os.mkfifo(fifo)
    got = _run_elsewhere({"PYSOLVER_CACHE_DIR": str(cache)}, timeout=120)
    assert got["success"] and got["info"]["kernel"] == "generated", got
    assert f"its {which} is not a regular file" in got["info"]["rebuilt"], got["info"]
    assert fifo.is_file()


@needs_gcc
def test_the_loader_checks_the_scene_record_after_dlopen(cache):
    """csrc/gen.c refuses (and closes) a library whose ps_gen_scene is not the one asked for."""
    from pysolver.build.bindings import ffi
    from pysolver.build.bindings import lib as clib
    model = pysolver.loads(DECK.format(mass=1.0))
    kernel = model.compile().kernel
    path = kernel.codegen["path"]
    msg = ffi.new("char[]", 512)
    wrong = kcache.RECORD + "0" * 64
    assert clib.ps_gen_open(path.encode(), wrong.encode(), kernel.m, msg, 512) == ffi.NULL
    assert ffi.string(msg).decode() == \
        f"{path} was generated for another scene (its scene record differs)"
    assert kernel.codegen["kernel"] == "generated" and model.run().success


# --- issue 23 item 4: faults of the generated code and its cache -------------------------------

@needs_gcc
def test_generated_c_is_iso_c99(cache, monkeypatch, tapes_answer):
    """No M_PI (not ISO C): the generated C compiles with gcc -std=c99 (HAVSIN reads pi)."""
    monkeypatch.setenv("CC", f"{GCC} -std=c99")
    model = pysolver.loads(DECK.format(mass=1.0))
    res = model.run()
    assert res.meta["kernel"] == "generated", res.log
    assert not _kernel_lines(res)
    assert "M_PI" not in codegen.source(model.compile().kernel)
    assert np.max(np.abs(res.y - tapes_answer.y)) < 1e-9


@needs_gcc
def test_a_compile_error_is_distinct_kept_and_not_retried(cache, tmp_path, monkeypatch,
                                                          tapes_answer):
    """A compiler that works but rejects the generated C: a distinct message (not "no
    compiler"), the source kept beside a failure marker, and no second compile in a later
    process."""
    bad = tmp_path / "bad.h"
    bad.write_text("#error this compiler setup rejects the generated code\n")
    calls = tmp_path / "calls"
    cc = _script(tmp_path, "picky-cc", f"""
if [ "$1" != --version ]; then echo compile >> {shlex.quote(str(calls))}; fi
exec {shlex.quote(GCC)} -include {shlex.quote(str(bad))} "$@"
""")
    monkeypatch.setenv("CC", str(cc))
    res = pysolver.loads(DECK.format(mass=1.0)).run()
    line = _on_tapes(res, tapes_answer, "the generated C failed to compile with",
                     "this compiler setup rejects the generated code")
    assert "no C compiler" not in line and "does not run" not in line and "\n" not in line
    (marker,) = cache.glob("*.failed")
    kept = marker.with_suffix(".c")
    assert str(kept) in line and str(marker) in line
    assert "ps_gen_scene" in kept.read_text()
    kcache._versions.clear()            # as a new process: only the marker on disk remembers
    again = pysolver.loads(DECK.format(mass=1.0)).run()
    line = _on_tapes(again, tapes_answer, "failed to compile", "in an earlier run",
                     "delete it to retry", "this compiler setup rejects the generated code")
    assert calls.read_text().split() == ["compile"]


def test_the_psgen_version_has_one_source():
    """The generated table takes PS_GEN_VERSION from pysolver.h, which the compiled kernel
    checks: no number of its own in the generator."""
    from pysolver.build.bindings import lib as clib
    from pysolver.headers import get_include
    assert not hasattr(emit, "VERSION")
    kernel = pysolver.loads(DECK.format(mass=1.0)).compile("tapes").kernel
    text = codegen.source(kernel)
    assert re.search(r"ps_gen_table = \{\n  PS_GEN_VERSION, ", text)
    header = (pathlib.Path(get_include()) / "pysolver.h").read_text()
    assert int(re.search(r"#define PS_GEN_VERSION (\d+)", header).group(1)) == \
        clib.PS_GEN_VERSION
