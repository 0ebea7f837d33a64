"""A Python routine that keeps state between calls is not traced (trial 45: the tracer ran
its paths one after another, the state carried from one to the next and froze into a wrong
expression, with success=True): it runs from the kernel, and res.meta["usersubs"] says why.
Routines without state still trace."""
import math
import types

import numpy as np
import pytest

import pysolver
from pysolver.deck.statecheck import keeps_state

from scenes import LINES_BRANCHY, LINES_PFOSUB

K = 4 * math.pi ** 2

SCENE = '''from pysolver.msolve import *
{routine}
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[2, 0, 0])
POINT_MASS(2, MASS=1.0, CM=10)
SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="USER(10)", ROUTINE={name})
REQUEST(1, F1="DX(10)", F2="SFORCE(1,0,2,1)")
INTEGRATOR(ERROR=1e-9{extra})
SIMULATE(TYPE="TRANSIENT", END=0.5, DTOUT=0.05)
'''

#: The spring pulls with K (xmax - 1), xmax the largest x reached so far, kept in each form of
#: state; x starts at its largest, 2, so the force is K toward marker 1: x = 2 - K t^2 / 2 to
#: x = 0 at t0 = 2 / sqrt(K), then x = -2 sqrt(K) (t - t0) + K (t - t0)^2 / 2. Traced, the
#: routine became IF(DX(10) - DX(10): ...), a spring following x (x = 1 + cos 2 pi t).
RUNNING_MAX = {
    "global": ("xmax = 0.0\n"
               "def sfo(id, time, par, npar, dflag, iflag):\n"
               "    global xmax\n"
               "    x = py_sysfnc('DX', [10])[0]\n"
               "    if iflag == 0:\n"
               "        xmax = max(xmax, x)\n"
               "    return -K*(xmax - 1)\n", "sfo", "sfo assigns the global xmax"),
    "list": ("xmax = [0.0]\n"
             "def sfo(id, time, par, npar, dflag, iflag):\n"
             "    x = py_sysfnc('DX', [10])[0]\n"
             "    if iflag == 0:\n"
             "        xmax[0] = max(xmax[0], x)\n"
             "    return -K*(xmax[0] - 1)\n", "sfo",
             "sfo reads the global xmax, a list that can change between calls"),
    "dict": ("seen = {}\n"
             "def sfo(id, time, par, npar, dflag, iflag):\n"
             "    x = py_sysfnc('DX', [10])[0]\n"
             "    if iflag == 0:\n"
             "        seen['max'] = max(seen.get('max', 0.0), x)\n"
             "    return -K*(seen.get('max', 0.0) - 1)\n", "sfo",
             "sfo reads the global seen, a dict that can change between calls"),
    "class attribute": ("class S:\n"
                        "    xmax = 0.0\n"
                        "def sfo(id, time, par, npar, dflag, iflag):\n"
                        "    x = py_sysfnc('DX', [10])[0]\n"
                        "    if iflag == 0:\n"
                        "        S.xmax = max(S.xmax, x)\n"
                        "    return -K*(S.xmax - 1)\n", "sfo",
                        "sfo sets the attribute xmax of an object"),
    "instance attribute": ("class Spring:\n"
                           "    def __init__(self):\n"
                           "        self.xmax = 0.0\n"
                           "    def sfo(self, id, time, par, npar, dflag, iflag):\n"
                           "        x = py_sysfnc('DX', [10])[0]\n"
                           "        if iflag == 0:\n"
                           "            self.xmax = max(self.xmax, x)\n"
                           "        return -K*(self.xmax - 1)\n"
                           "spring = Spring()\n", "spring.sfo",
                           "it is a method of a Spring object"),
    "closure cell": ("def make():\n"
                     "    xmax = 0.0\n"
                     "    def sfo(id, time, par, npar, dflag, iflag):\n"
                     "        nonlocal xmax\n"
                     "        x = py_sysfnc('DX', [10])[0]\n"
                     "        if iflag == 0:\n"
                     "            xmax = max(xmax, x)\n"
                     "        return -K*(xmax - 1)\n"
                     "    return sfo\n"
                     "sfo = make()\n", "sfo",
                     "sfo assigns the enclosing function's variable xmax (nonlocal)"),
    "mutable default": ("def sfo(id, time, par, npar, dflag, iflag, xmax=[0.0]):\n"
                        "    x = py_sysfnc('DX', [10])[0]\n"
                        "    if iflag == 0:\n"
                        "        xmax[0] = max(xmax[0], x)\n"
                        "    return -K*(xmax[0] - 1)\n", "sfo",
                        "sfo has a mutable default argument (a list)"),
}


def _run(routine, name, extra=""):
    deck = SCENE.format(routine=f"K = {K!r}\n{routine}", name=name, extra=extra)
    return pysolver.loads(deck, fmt="py").run()


def _how(res):
    (how,) = res.meta["usersubs"].values()
    return how


@pytest.mark.parametrize("form", list(RUNNING_MAX))
def test_a_running_maximum_in_each_form_of_state_runs_from_the_kernel(form):
    """x from a force K toward marker 1 (x never exceeds its start), against 1 + cos 2 pi t
    when traced; the kernel's difference steps (6e-6 of x) enter the kept maximum, 1e-5 at
    most in x."""
    routine, name, why = RUNNING_MAX[form]
    res = _run(routine, name)
    assert res.success, res.message
    assert f"Python callback (not traced: it may keep state between calls: {why}), called " \
           "from the kernel" in _how(res)
    t = np.asarray(res.t)
    t0 = 2 / math.sqrt(K)
    x = np.where(t <= t0, 2 - K * t * t / 2,
                 -2 * math.sqrt(K) * (t - t0) + K * (t - t0) ** 2 / 2)
    np.testing.assert_allclose(res.request(1)[:, 0], x, rtol=0, atol=2e-5)
    np.testing.assert_allclose(abs(res.request(1)[:, 1]), K, rtol=1e-5)


def test_the_trials_latch_runs_from_the_kernel_and_lets_go_at_x_1_5():
    """Trial 45's repro: a global latch, set once x < 1.5. The closed form: x = 1 + cos 2 pi t
    to t = 1/6, then coasting at -2 pi sin(pi / 3). IDA's trial calls may set the latch a
    little early: within 5e-3 at HMAX = 1e-3 (traced, x stayed 2 and the force 0)."""
    routine = ("latched = False\n"
               "def sfo(id, time, par, npar, dflag, iflag):\n"
               "    global latched\n"
               "    x = py_sysfnc('DX', [10])[0]\n"
               "    if iflag == 0 and x < 1.5:\n"
               "        latched = True\n"
               "    if latched:\n"
               "        return 0.0\n"
               "    return -K*(x - 1)\n")
    res = _run(routine, "sfo", ", HMAX=1e-3")
    assert res.success, res.message
    assert "(not traced: it may keep state between calls: sfo assigns the global latched)" \
        in _how(res)
    t = np.asarray(res.t)
    ts, v = 1 / 6, -2 * math.pi * math.sin(math.pi / 3)
    x = np.where(t <= ts, 1 + np.cos(2 * math.pi * t), 1.5 + v * (t - ts))
    np.testing.assert_allclose(res.request(1)[:, 0], x, rtol=0, atol=5e-3)
    assert res.request(1)[0, 1] == pytest.approx(-K, rel=1e-9)
    np.testing.assert_array_equal(res.request(1)[t > 0.25, 1], 0.0)


def test_a_routine_without_state_still_traces():
    """Constants, the math module, NumPy, a helper function and a tuple of numbers are not
    state: the routine is traced into the expression."""
    routine = ("import numpy as np\n"
               "GAINS = (1.0, 2.0)\n"
               "def helper(x):\n"
               "    return x - 1\n"
               "def sfo(id, time, par, npar, dflag, iflag):\n"
               "    x = py_sysfnc('DX', [10])[0]\n"
               "    parts = [0.0, 0.0]\n"
               "    parts[0] = -K*GAINS[0]*helper(x)\n"
               "    return np.sum(np.array(parts))\n")
    res = _run(routine, "sfo")
    assert res.success, res.message
    assert "traced into the kernel" in _how(res)
    t = np.asarray(res.t)
    np.testing.assert_allclose(res.request(1)[:, 0], 1 + np.cos(2 * math.pi * t), atol=1e-6)


def _fn(source, name="PFOSUB", namespace=None):
    namespace = dict(namespace or {})
    exec(compile(source, "<routine>", "exec"), namespace)
    return namespace[name]


@pytest.mark.parametrize("source", [LINES_PFOSUB, LINES_BRANCHY])
def test_the_seed_routines_keep_no_state(source):
    assert keeps_state(_fn(source)) is None


@pytest.mark.parametrize("source, name, why", [
    ("import random\ndef f(t):\n    return random.random()\n", "f",
     "f uses the module random, whose functions keep state"),
    ("import numpy as np\ndef f(t):\n    return np.random.rand()\n", "f",
     "f uses the module numpy.random, whose functions keep state"),
    ("gain = 1.0\ndef set_gain(g):\n    global gain\n    gain = g\n"
     "def f(t):\n    return gain * t\n", "f",
     "f reads the global gain, which set_gain assigns"),
    ("import numpy as np\nTABLE = np.zeros(3)\ndef f(t):\n    return TABLE[0] * t\n", "f",
     "f reads the global TABLE, a NumPy array that can change between calls"),
    ("state = [0]\ndef bump():\n    state[0] += 1\n    return state[0]\n"
     "def f(t):\n    return bump() * t\n", "f",
     "f calls bump: bump reads the global state, a list that can change between calls"),
    ("def f(t):\n    globals()['n'] = 1\n    return t\n", "f", "f calls globals"),
    ("def f(t):\n    return (lambda: [v.append(1) for v in CELLS])()\nCELLS = ([],)\n", "f",
     "f reads the global CELLS, a list that can change between calls"),
])
def test_reads_and_writes_of_state_are_found(source, name, why):
    assert keeps_state(_fn(source, name)) == why


@pytest.mark.parametrize("source, why", [
    ("from random import random\ndef f(t):\n    return random()*t\n",
     "f reads the global random, a method of a Random object that can change between calls"),
    ("from time import perf_counter\ndef f(t):\n    return perf_counter()\n",
     "f reads the global perf_counter, a function of the module time that can change between "
     "calls"),
    ("_flags = set()\n_set = _flags.add\ndef f(t):\n    _set('x')\n    return t\n",
     "f reads the global _set, a method of a set that can change between calls"),
    ("import itertools\ncount = itertools.count().__next__\ndef f(t):\n    return count()*t\n",
     "f reads the global count, a method of a count object that can change between calls"),
    ("import functools\ndef _acc(store, x):\n    store.append(x)\n    return max(store)\n"
     "track = functools.partial(_acc, [])\ndef f(t):\n    return track(t)\n",
     "f reads the global track, a list that can change between calls"),
    ("def f(t):\n    d = f.__dict__\n    d['m'] = max(d.get('m', 0.0), t)\n    return d['m']\n",
     "f reads an object's __dict__"),
    ("def f(t):\n    from numpy import random as r\n    return r.rand()*t\n",
     "f imports the module numpy.random"),
    ("import functools\n@functools.lru_cache\ndef h(x):\n    return x\n"
     "def f(t):\n    return h(1)*t\n",
     "f reads the global h, a cached function (_lru_cache_wrapper) that can change between "
     "calls"),
    ("import sys\ndef f(t):\n    return getattr(sys.modules['__main__'], 'x', 0)*t\n",
     "f reads the global sys.modules, a dict that can change between calls"),
])
def test_state_behind_library_objects_is_found(source, why):
    """State kept in a builtin object's bound method, a library function that keeps state
    (random, time), a functools.partial's arguments, a function's __dict__, an import inside
    the call, a cache, or a library module's mutable data (the review of stop 45)."""
    assert keeps_state(_fn(source, "f")) == why


def test_a_latch_kept_in_a_set_runs_from_the_kernel():
    """The trial's latch written with a set's add and membership test: not traced (it had
    been traced into IF(DX - 1.5: 0, 0, 0), the body never moving), so the spring pulls the
    mass from x = 2 at once."""
    routine = ("_flags = set()\n_set, _has = _flags.add, _flags.__contains__\n"
               "def sfo(id, time, par, npar, dflag, iflag):\n"
               "    x = py_sysfnc('DX', [10])[0]\n"
               "    if iflag == 0 and x < 1.5:\n"
               "        _set('latched')\n"
               "    return 0.0 if _has('latched') else -K*(x - 1)\n")
    res = _run(routine, "sfo")
    assert res.success, res.message
    assert "not traced: it may keep state between calls" in _how(res)
    t = np.asarray(res.t)
    early = t < 1 / 6 - 0.02
    np.testing.assert_allclose(res.request(1)[early, 0], 1 + np.cos(2 * math.pi * t[early]),
                               atol=1e-4)


def test_callables_that_are_not_plain_functions_are_not_traced():
    class Obj:
        def __call__(self, t):
            return t
    assert keeps_state(Obj()) == "it is an Obj object, not a plain function: its state " \
        "cannot be seen"
    assert keeps_state(types.MethodType(lambda self, t: t, Obj())) == \
        "it is a method of an Obj object"


def test_a_traced_value_kept_from_an_earlier_path_fails_the_trace():
    """The tracer's own net, for state the bytecode rules cannot see: a stand-in made on one
    path of the branches and used on the next is refused."""
    from pysolver.deck import tracer
    kept = []

    def run():
        with tracer.active():
            x = tracer.py_sysfnc("DX", [10])[0]
            top = kept[0] if kept else x
            kept.append(x)
            return tracer.tree_of((top - 1) if x < 1.5 else top)

    with pytest.raises(tracer.Untraceable) as err:
        tracer.explore(run)
    assert str(err.value) == "it keeps state between calls: a traced value from an earlier " \
        "call was used"
