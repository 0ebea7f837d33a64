"""Generated C per deck (pysolver.build.codegen) against the tape interpreter it replaces, and
its disk cache: agreement to rounding on every deck, cache hits, broken entries, no compiler."""
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import pysolver
from pysolver.build import codegen

from helpers import DECKS, ROOT, TEST_DECKS
from scenes import chain_deck, rigid_chain_deck

ALL_DECKS = sorted(DECKS.glob("*.xml")) + sorted(DECKS.glob("*.py")) + \
    sorted(TEST_DECKS.glob("*.xml"))

TINY = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="2" body_id="2" pos_z="1"/>
  <Body_Point id="2" cg_id="2" mass="{mass}"/><Force_Gravity grav_z="-9.81"/>
  <Force_Penalty id="1" expr="0.5 - DZ(2)" unilateral="TRUE" penalty="1e3" penalty1="5"/>
  <Post_Request id="1" expr1="DZ(2)" expr2="PFORCE(1)" name1="z" name2="f"/>
  <Param_Transient integr_tol="1e-6"/></Model>
  <Simulate analysis_type="Transient" end_time="0.5" print_interval="0.1"/></MotionSolve>"""


def _close(a, b, what):
    """Agreement to a few units of rounding of the larger terms: the two kernels add the same
    terms in different orders. NaN (a NULL channel) must be NaN in both."""
    nan = np.isnan(b)
    assert np.array_equal(np.isnan(a), nan), what
    a, b = a[~nan], b[~nan]
    if b.size:
        scale = max(1.0, float(np.max(np.abs(b))))
        err = float(np.max(np.abs(a - b)))
        assert err <= 1e-13 * scale, f"{what}: {err:.3g} (scale {scale:.3g})"


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty kernel cache for one test."""
    monkeypatch.setenv("PYSOLVER_CACHE_DIR", str(tmp_path / "kernels"))
    return tmp_path / "kernels"


@pytest.fixture(params=["straight", "looped"])
def form(request, monkeypatch):
    """Generate every deck as straight-line C (a small deck's form), or as looped C (a large
    deck's)."""
    monkeypatch.setattr(codegen, "STRAIGHT", 0 if request.param == "looped" else 10 ** 9)
    return request.param


@pytest.mark.parametrize("path", ALL_DECKS, ids=lambda p: p.name)
def test_generated_and_tape_kernels_agree(path, form):
    """Residual, iteration matrix, sensor expressions and request channels agree to rounding
    at random states, for every deck (all element types and expression functions), in both
    forms of generated C."""
    model = pysolver.load(path)
    gen, tape = model.compile("generated").kernel, model.compile("tapes").kernel
    assert gen.codegen["kernel"] == "generated", gen.codegen
    assert tape.codegen["kernel"] == "tapes"
    assert codegen.is_looped(gen) == (form == "looped")
    _agree(gen, tape)


def _agree(gen, tape):
    rng = np.random.default_rng(7)
    y0 = gen.layout.initial_state()
    for _ in range(4):
        t = float(rng.uniform(0.0, 2.0))
        y = y0 + 0.05 * rng.normal(size=gen.ny)
        yp = rng.normal(size=gen.ny)
        cj = 10.0 ** rng.uniform(-1, 3)
        _close(gen.residual_array(t, y, yp), tape.residual_array(t, y, yp), "residual")
        _close(gen.jacobian_array(t, y, yp, cj), tape.jacobian_array(t, y, yp, cj), "Jacobian")
        _close(gen.jacobian_csc_array(t, y, yp, cj).toarray(),
               tape.jacobian_array(t, y, yp, cj), "sparse Jacobian")
        _close(gen.sensor_status(t, y, yp)[0], tape.sensor_status(t, y, yp)[0], "sensors")
        _close(gen.outputs(t, y, yp), tape.outputs(t, y, yp), "outputs")


def test_runs_agree_and_say_which_kernel(decks):
    """A whole run on either kernel: the same steps and answers to rounding of the error
    control, and the metadata says which kernel ran."""
    model = pysolver.load(decks / "particle_between_lines.xml")
    gen, tape = model.run(), model.run(kernel="tapes")
    assert gen.success and tape.success
    assert gen.meta["kernel"] == "generated" and tape.meta["kernel"] == "tapes"
    assert abs(gen.stats["steps"] - tape.stats["steps"]) <= 2
    assert np.max(np.abs(gen.y[-1] - tape.y[-1])) < 1e-7


def test_warm_load_neither_generates_nor_compiles(cache):
    first = pysolver.loads(TINY.format(mass=1.0))
    res = first.run()
    info = first.compile().kernel.codegen
    assert info["kernel"] == "generated" and not info["cached"]
    assert res.timing["compile"] > 0 and res.timing["generate"] > 0
    assert "compiled in" in res.summary()
    again = pysolver.loads(TINY.format(mass=1.0))
    res2 = again.run()
    info2 = again.compile().kernel.codegen
    assert info2["cached"] and info2["compile"] == 0.0 and info2["generate"] == 0.0
    assert info2["path"] == info["path"]
    assert res2.timing["compile"] == 0.0 and "compiled in" not in res2.summary()
    assert np.array_equal(res.y, res2.y)


def test_values_read_at_run_time_share_one_library(cache):
    """A mass is read from the model's arrays, so decks that differ only there share one
    library, and each runs with its own mass: the momentum rows differ by dm (v' - g)."""
    light, heavy = (pysolver.loads(TINY.format(mass=m)) for m in (1.0, 3.0))
    kl, kh = light.compile().kernel, heavy.compile().kernel
    assert kl.codegen["path"] == kh.codegen["path"] and kh.codegen["cached"]
    rng = np.random.default_rng(3)
    y = kl.layout.initial_state() + 0.1 * rng.normal(size=6)
    yp = rng.normal(size=6)
    diff = kh.residual_array(0.0, y, yp) - kl.residual_array(0.0, y, yp)
    expected = np.r_[0.0, 0.0, 0.0, 2.0 * (yp[3:] - [0.0, 0.0, -9.81])]
    assert np.max(np.abs(diff - expected)) < 1e-12


def test_broken_cache_entry_is_rebuilt_not_loaded(cache, tmp_path):
    """An entry truncated after it was built (here by another process, which built it) does
    not match its digest: it is compiled again, never loaded."""
    script = f"import pysolver; pysolver.loads({TINY.format(mass=1.0)!r}).compile().kernel"
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    subprocess.run([sys.executable, "-c", script], env=env, cwd=tmp_path, check=True)
    (lib,) = cache.glob("*.so")
    lib.write_bytes(lib.read_bytes()[:100])
    model = pysolver.loads(TINY.format(mass=1.0))
    info = model.compile().kernel.codegen
    assert info["kernel"] == "generated" and not info["cached"] and info["compile"] > 0
    assert model.run().success
    assert pysolver.loads(TINY.format(mass=1.0)).compile().kernel.codegen["cached"]


def test_no_compiler_runs_the_tapes_with_one_log_line(cache, monkeypatch):
    monkeypatch.setenv("CC", "/nonexistent")
    model = pysolver.loads(TINY.format(mass=1.0))
    res = model.run()
    assert res.success and res.meta["kernel"] == "tapes"
    lines = [line for line in res.log if line.startswith("kernel:")]
    assert len(lines) == 1 and "/nonexistent" in lines[0], res.log
    assert not list(cache.glob("*.so"))
    monkeypatch.delenv("CC")
    ref = pysolver.loads(TINY.format(mass=1.0)).run()
    assert ref.meta["kernel"] == "generated"
    assert np.max(np.abs(ref.y - res.y)) < 1e-9


def test_a_scene_over_the_size_limit_runs_the_tapes(cache, monkeypatch):
    monkeypatch.setattr(codegen, "LIMIT", 50)
    model = pysolver.loads(TINY.format(mass=1.0))
    res = model.run()
    assert res.success and res.meta["kernel"] == "tapes"
    assert any("too large" in line for line in res.log), res.log


def test_the_generated_source_is_split_into_bounded_functions(monkeypatch):
    """Large decks compile as many small functions, never one giant one: each holds at most
    CHUNK temporaries, or computes one expression that alone needs more."""
    from pysolver.build.codegen import emit
    monkeypatch.setattr(emit, "CHUNK", 40)
    # straight-line C (all_functions.xml, with its three tracked angles, is just past
    # STRAIGHT's estimate and would be looped)
    monkeypatch.setattr(codegen, "STRAIGHT", 10 ** 6)
    kernel = pysolver.load(TEST_DECKS / "all_functions.xml").compile("tapes").kernel
    text = codegen.source(kernel)
    bodies = re.findall(r"static void psg_jacobian_\d+\(.*?\n}\n", text, re.S)
    assert len(bodies) > 5
    for body in bodies:
        assert body.count("const double t") <= 40 or body.count("  out[") == 1


def _chain_with_requests(n, **kw):
    """chain_deck(n) with a request on every body (its x and z)."""
    reqs = "".join(f'<Post_Request id="{10 + i}" expr1="DX({1000 + i})" expr2="DZ({1000 + i})"/>'
                   for i in range(n))
    return chain_deck(n, **kw).replace("<Param_Transient", reqs + "<Param_Transient")


def test_a_large_deck_is_looped_in_code_independent_of_its_size():
    """A chain with a request on every body is generated as one function per shape of body,
    link and request, looped over tables: ten times the links give the same functions (so the
    same compile work, bar the tables), and the kernel agrees with the tapes."""
    small, large = (pysolver.loads(_chain_with_requests(n)).compile("tapes").kernel
                    for n in (80, 800))
    assert codegen.is_looped(small) and codegen.is_looped(large)
    functions = [re.findall(r"static void (psg_\w+)\(", codegen.source(k)) for k in (small, large)]
    assert functions[0] == functions[1]
    assert len([f for f in functions[0] if re.fullmatch(r"psg_r\d+", f)]) == 3  # body, 2 links
    assert len([f for f in functions[0] if re.fullmatch(r"psg_o\d+", f)]) == 2  # 2 kinds
    model = pysolver.loads(_chain_with_requests(800, end_time=0.05))
    gen, tape = model.compile("generated").kernel, model.compile("tapes").kernel
    assert gen.codegen["kernel"] == "generated", gen.codegen
    _agree(gen, tape)
    a, b = model.run(), model.run(kernel="tapes")
    # the kernels round differently, which may flip a step decision; the answers agree far
    # inside the tolerance (1e-6)
    assert a.success and b.success and abs(a.stats["steps"] - b.stats["steps"]) <= 2
    assert np.max(np.abs(a.y[-1] - b.y[-1])) < 1e-8
    assert np.max(np.abs(a.request(809)[-1] - b.request(809)[-1]), initial=0.0,
                  where=~np.isnan(b.request(809)[-1])) < 1e-8


def test_rigid_bodies_turned_differently_share_templates():
    """A chain of rigid bodies whose markers differ in orientation from link to link: the
    orientations are read at run time, so the links share templates (the same functions for
    20 and 40 links) and the deck is generated, not left to the tapes; it agrees with them."""
    small, large = (pysolver.loads(rigid_chain_deck(n)).compile("tapes").kernel for n in (20, 40))
    assert codegen.is_looped(small) and codegen.is_looped(large)
    functions = [re.findall(r"static void (psg_\w+)\(", codegen.source(k, codegen.LIMIT))
                 for k in (small, large)]
    assert functions[0] == functions[1]
    model = pysolver.loads(rigid_chain_deck(40))
    gen, tape = model.compile("generated").kernel, model.compile("tapes").kernel
    assert codegen.is_looped(gen) and gen.codegen["kernel"] == "generated", gen.codegen
    _agree(gen, tape)


def test_looped_decks_differing_only_in_constants_share_one_library(cache):
    """Looped C reads every constant at run time: a chain whose links are 0.12 long instead of
    0.1 (a constant in an expression, not a sweep parameter) loads the same library, and its
    residual sees its own length (the link force at the initial state changes)."""
    text = chain_deck(60)
    short, long = (pysolver.loads(t) for t in (text, text.replace(") - 0.1", ") - 0.12")))
    ks, kl = short.compile().kernel, long.compile().kernel
    assert codegen.is_looped(ks) and ks.codegen["path"] == kl.codegen["path"]
    assert kl.codegen["cached"]
    y = ks.layout.initial_state()
    yp = np.zeros_like(y)
    _close(kl.residual_array(0.0, y, yp), long.compile("tapes").kernel.residual_array(0.0, y, yp),
           "residual")
    assert not np.allclose(kl.residual_array(0.0, y, yp), ks.residual_array(0.0, y, yp))


@pytest.mark.parametrize("deck", ["static_pendulum.xml", "quasi_static_stack.xml"])
def test_statics_run_on_the_kernel_the_run_asked_for(deck, decks):
    """Static and quasi-static commands (MKEAM's undamped kernel too) use the run's kernel
    kind: a run with kernel="tapes" builds no generated kernel, and finds the same equilibria."""
    model = pysolver.load(decks / deck)
    tapes = model.run(kernel="tapes")
    assert tapes.success and model.compiled_kernels == ("tapes",)
    gen = model.run()
    assert gen.success and gen.meta["kernel"] == "generated"
    assert len(tapes.statics) == len(gen.statics) > 0
    assert np.max(np.abs(tapes.y - gen.y)) < 1e-8
