"""Hard cases for penalty models: stiffness and smoothing over decades (issue 5, part).

Each run must complete, come to rest at the force balance, and stay within a step budget
(measured values with about 30 % margin)."""
import numpy as np
import pytest

import pysolver
from pysolver.solve import cida

#: the budgets below are those of the default path, IDA driven from C with its step control
needs_c = pytest.mark.skipif(not cida.available(),
                             reason="the scikit-sundae wheel ships no SUNDIALS libraries")


def rest_penetration(k, mg, s):
    """Root of 2 k g STEP(g, 0, 0, s, 1) = m g, also beyond the smoothing band."""
    lo, hi = 0.0, max(s, mg / k)
    for _ in range(200):
        g = 0.5 * (lo + hi)
        d = min(g / s, 1.0)
        if 2 * k * g * d * d * (3 - 2 * d) > mg:
            hi = g
        else:
            lo = g
    return 0.5 * (lo + hi)

# (penalty N/mm, smoothing mm): step budget
CASES = {(1e2, 1.0): 650, (1e2, 1e-2): 620, (1e4, 1.0): 700, (1e4, 1e-2): 760,
         (1e4, 1e-4): 720, (1e6, 1e-2): 2100, (1e6, 1e-4): 750, (1e8, 1e-4): 13500}


@pytest.mark.parametrize("k,s", list(CASES), ids=[f"k{k:g}-s{s:g}" for k, s in CASES])
def test_seed3_over_stiffness_and_smoothing(decks, k, s):
    text = (decks / "particle_between_lines.xml").read_text().replace(
        'penalty="1E4"', f'penalty="{k:g}"').replace('smoothing_factor="1.0"',
                                                     f'smoothing_factor="{s:g}"')
    end = 10.0 if k < 1e3 else 3.0
    text = text.replace('end_time="3.0"', f'end_time="{end}"')
    res = pysolver.loads(text).run()
    assert res.success, res.message
    x, z = res.request(1)[-1, :2]
    g = rest_penetration(k, 9.81, s)
    assert abs(x) < 1e-4 and abs(z - (1 - g)) < 1e-4, (x, z, 1 - g)
    assert res.stats["steps"] <= CASES[(k, s)]


def test_undamped_contact_keeps_energy(decks):
    """penalty1 = 0: a conservative bouncing particle; its energy stays constant to tolerance."""
    text = (decks / "particle_between_lines.xml").read_text().replace(
        'penalty1="1E2"', 'penalty1="0"').replace('integr_tol="1e-6"', 'integr_tol="1e-9"')
    text = text.replace('end_time="3.0"', 'end_time="1.0"')
    res = pysolver.loads(text).run()
    assert res.success
    x, z = res.request(1)[:, 0], res.request(1)[:, 1]
    vx, vz = res.y[:, 3], res.y[:, 5]

    def potential(g):
        gp = np.clip(g, 0, None)
        d = np.clip(gp, 0, 1)
        # integral of k g S(g) for S = d^2 (3 - 2 d) on [0, 1], linear k g beyond
        inside = 1e4 * (0.75 * d ** 4 - 0.4 * d ** 5)
        return np.where(gp <= 1, inside, 1e4 * (0.35 + 0.5 * (gp ** 2 - 1)))

    E = 0.5 * (vx ** 2 + vz ** 2) + 9810 * z + 1000 * (potential(1 + x - z) + potential(1 - x - z))
    assert np.abs(E - E[0]).max() < 1e-5 * E[0]


def test_resting_on_a_sharp_contact_does_not_chatter():
    """A particle at rest on a floor with a tiny smoothing band: no step collapse."""
    deck = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="10" body_id="2" pos_z="-1e-6"/><Body_Point id="2" cg_id="10" mass="1"/>
      <Force_Gravity grav_z="-9.81"/>
      <Force_Penalty id="1" expr="-DZ(10)" penalty="1e7" penalty1="1e3" unilateral="TRUE" smoothing_factor="1e-6"/>
      <Post_Request id="1" expr1="DZ(10)" expr2="PFORCE(1)"/></Model>
      <Simulate analysis_type="Transient" end_time="10" print_interval="0.1"/></MotionSolve>"""
    res = pysolver.loads(deck).run(integr_tol=1e-6)
    assert res.success and res.stats["steps"] < 400
    np.testing.assert_allclose(res.request(1)[-10:, 1], -9.81, rtol=1e-6)


@needs_c
@pytest.mark.parametrize("s", [1e-4, 1e-6])
def test_seed3_at_penalty_1e10(decks, s):
    """Penalty 1e10 N/mm with the seed's damping 1e2: nearly elastic contact, the particle keeps
    bouncing in the V. The run completes within a step budget, never gains energy, and the
    penetration stays below the elastic bound sqrt(2 E0 / (1000 k)) = 4.8e-4 mm."""
    text = (decks / "particle_between_lines.xml").read_text().replace(
        'penalty="1E4"', 'penalty="1e10"').replace('smoothing_factor="1.0"',
                                                   f'smoothing_factor="{s:g}"')
    res = pysolver.loads(text).run(backend="c")
    assert res.success, res.message
    # the bouncing is chaotic: rounding changes the step count, 11,548 to 112,242 over runs
    # at integr_tol within 2e-4 of 1e-6 with either dense solver (stop 38: 32 runs); what
    # must not happen is the step-growth limit switched on by the impacts (it was once:
    # 54,438 steps), or a run that creeps
    assert res.stats["growth_limited_at"] is None
    assert res.stats["steps"] < 300000
    x, z = res.request(1)[:, 0], res.request(1)[:, 1]
    vx, vz = res.y[:, 3], res.y[:, 5]
    energy = 0.5 * (vx ** 2 + vz ** 2) + 9810 * z   # kinetic + gravity, <= total (potential >= 0)
    assert energy.max() <= energy[0] * (1 + 1e-6)
    assert max((1 + x - z).max(), (1 - x - z).max()) < 4.8e-4


# penalty (N/m) of the pendulum rod: step budget at integr_tol 1e-8 over 2 s (measured + 30 %;
# at 1e10 for the median of PENDULUM_SPREAD runs, the larger of the two dense solvers', see
# the test)
PENDULUM_BUDGET = {1e2: 420, 1e4: 560, 1e6: 1150, 1e8: 3500, 1e10: 9100}

#: Relative changes of integr_tol 1e-8 over which k = 1e10's runs are taken.
PENDULUM_SPREAD = np.linspace(-1e-4, 1e-4, 9)


def pendulum_deck(k, end=2.0, c=None, dt=0.01):
    c = 2 * np.sqrt(k) if c is None else c          # critical damping of the 1 kg mass
    return f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/><Reference_Marker id="10" body_id="2" pos_x="1"/>
<Body_Point id="2" cg_id="10" mass="1"/><Force_Gravity grav_y="-9.81"/>
<Force_Penalty id="1" expr="DM(10,1) - 1" penalty="{k:g}" penalty1="{c:g}"/>
<Post_Request id="1" expr1="DX(10)" expr2="DY(10)"/></Model>
<Simulate analysis_type="Transient" end_time="{end}" print_interval="{dt}"/></MotionSolve>"""


def rigid_pendulum_distance(res):
    from scipy.integrate import solve_ivp
    sol = solve_ivp(lambda t, s: [s[1], -9.81 * np.cos(s[0])], (0, res.t[-1]), [0, 0],
                    t_eval=res.t, rtol=1e-12, atol=1e-12, method="DOP853")
    xy = res.request(1)
    return np.hypot(xy[:, 0] - np.cos(sol.y[0]), xy[:, 1] - np.sin(sol.y[0])).max()


@needs_c
def test_penalty_pendulum_over_eight_decades():
    """A point-mass pendulum on a critically damped penalty rod, k = 1e2 ... 1e10: every run
    completes in its step budget, and the distance from the rigid pendulum falls as 1/k until
    the tolerance takes over (measured 0.60, 1.4e-2, 1.4e-4, 1.9e-5, 1.1e-5). Where the
    tolerance rules, the error is a matter of the step sequence, which rounding changes: at
    integr_tol within 1e-4 of 1e-8, k = 1e8 gave 5.7e-6..1.9e-5 and k = 1e10 1.1e-5..7.3e-5
    (stop 38, nine runs each with either dense solver), so the bound is twice the largest.
    At k = 1e10 the step count is rounding's too: nine runs within 1e-4 of 1e-8 took
    5,151-14,131 steps with pysolver's dense solver and 5,112-41,921 with SUNDIALS' (medians
    5,809 and 7,001; stop 41), and IDA as shipped (growth 2, Newton 0.33) 0.8-1.3 million. So
    k = 1e10 is judged on nine runs: their median within the budget, and every one within
    100,000 steps, a tenth of IDA's own."""
    err = {}
    for k, budget in PENDULUM_BUDGET.items():
        # the C driver: its step-growth limit is what keeps k >= 1e6 short
        model = pysolver.loads(pendulum_deck(k))
        tols = 1e-8 * (1 + PENDULUM_SPREAD) if k == 1e10 else [1e-8]
        runs = [model.run(integr_tol=tol, backend="c") for tol in tols]
        steps = [res.stats["steps"] for res in runs]
        assert all(res.success for res in runs), (k, [res.message for res in runs])
        assert np.median(steps) <= budget and max(steps) < 100_000, (k, steps)
        err[k] = max(rigid_pendulum_distance(res) for res in runs)
    assert 60 < err[1e4] / err[1e6] < 150           # O(1/k) in the model-limited range
    assert err[1e8] < 4e-5 and err[1e10] < 1.5e-4


def _resident_bytes():
    import os
    with open(f"/proc/{os.getpid()}/statm") as fh:
        return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


@needs_c
def test_long_run_has_constant_work_per_step_and_no_memory_growth():
    """150,000 steps (undamped k = 1e8 rod, integr_tol 1e-8): twice the simulated time costs
    twice the steps with the same residuals and Jacobians per step, and neither Python nor the
    process grows with the number of steps (the kernel allocates nothing while integrating)."""
    import tracemalloc
    short = pysolver.loads(pendulum_deck(1e8, end=5.0, c=0.0, dt=0.05))
    long = pysolver.loads(pendulum_deck(1e8, end=10.0, c=0.0, dt=0.1))   # same 101 outputs
    # a fixed step control (the automatic limit would switch on part-way through)
    opts = dict(integr_tol=1e-8, backend="c", max_step_growth=1.1)
    short.run(**opts)                                # warm-up: libraries, compiled kernels,
    long.run(**opts)                                 # cached run settings

    rss0 = _resident_bytes()
    tracemalloc.start()
    a = short.run(**opts)
    peak_short = tracemalloc.get_traced_memory()[1]
    tracemalloc.reset_peak()
    b = long.run(**opts)
    peak_long = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    rss1 = _resident_bytes()
    assert a.success and b.success and b.stats["steps"] >= 100000
    assert 1.6 < b.stats["steps"] / a.stats["steps"] < 2.4
    per_a, per_b = a.stats["nres"] / a.stats["steps"], b.stats["nres"] / b.stats["steps"]
    assert abs(per_b - per_a) < 0.15 * per_a
    # Jacobians stay rare (measured 1 per 650-700 steps) in both
    assert a.stats["njac"] < 0.01 * a.stats["steps"] and b.stats["njac"] < 0.01 * b.stats["steps"]
    assert peak_long < 1.2 * peak_short + 65536
    assert rss1 - rss0 < 2 ** 20
