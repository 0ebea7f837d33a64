"""Batch-study throughput: 1000 cases of seed example 3 (penalty of line 1 x initial x of the
particle, a 40 x 25 grid), cases per second

- by the hand-written loop (edit the deck text, load, run) on 100 of the cases,
- by pysolver.sweep in this process (processes=0), with 2 worker processes (the first sweep
  starts the worker server; the second reuses it) and on a 2-worker Dask LocalCluster,

against the plain C program (benchmarks/c_ida/seed3_ida: a hand-written residual and
Jacobian on the same SUNDIALS IDA, the same cases one after another in one process, best of 3
passes), and the two ratios issue 27 sets targets for: a sweep's cost per case against a warm
``model.run(params=case)`` of the same cases (target <= 1.15), and that warm run against the
plain C program (target <= 1.3), both at the deck's integr_tol 1e-6.

Run: ``python benchmarks/sweep.py``.
"""
import tempfile
import time

import numpy as np

import pysolver

from scenes import DECKS
from work_precision import c_program

DECK = DECKS / "particle_between_lines.xml"
PEN, POS = "Force_Penalty/1/penalty", "Reference_Marker/10/pos_x"


def cases():
    return pysolver.grid({PEN: np.linspace(5e3, 2e4, 40), POS: np.linspace(80.0, 110.0, 25)})


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def hand_loop(cs):
    text = DECK.read_text()
    for c in cs:
        t = text.replace('pos_x="100"', f'pos_x="{c[POS]!r}"').replace(
            'expr="1+dx(10)-dz(10)"\n                   penalty="1E4"',
            f'expr="1+dx(10)-dz(10)"\n                   penalty="{c[PEN]!r}"')
        pysolver.loads(t).run()


def plain_c(cs, repeat=3, ny=4):
    """The plain C program on the cases, on `ny` states (4: x z vx vz; 6: the particle's three
    coordinates, as pysolver integrates it): (seconds of the best pass, steps of a pass)."""
    with tempfile.NamedTemporaryFile("w", suffix=".txt") as fh:
        fh.write("".join(f"{c[PEN]!r} {c[POS]!r}\n" for c in cs))
        fh.flush()
        (n, steps, sec), _ = c_program("seed3_ida", "1e-06", repeat, fh.name, ny)
    assert int(n) == len(cs)
    return sec, int(steps)


def warm_runs(model, cs, repeat=3):
    """model.run(params=case) over the cases, best of `repeat` passes: (seconds, steps)."""
    best, steps = float("inf"), 0
    for _ in range(repeat):
        t0 = time.perf_counter()
        steps = sum(model.run(progress=False, params=c).stats["steps"] for c in cs)
        best = min(best, time.perf_counter() - t0)
    return best, steps


def main():
    cs = cases()
    model = pysolver.load(DECK)
    model.run()
    runs, run_steps = warm_runs(model, cs)
    c_time, c_steps = plain_c(cs)
    c6_time, c6_steps = plain_c(cs, ny=6)
    hand, _ = timed(lambda: hand_loop(cs[:100]))
    hand /= 100
    serial = float("inf")
    for _ in range(3):
        t, sw = timed(lambda: pysolver.sweep(model, cs, processes=0))
        serial = min(serial, t)
    assert sw.counts()["ok"] == len(cs)
    cold, _ = timed(lambda: pysolver.sweep(model, cs, processes=2))
    warm, _ = timed(lambda: pysolver.sweep(model, cs, processes=2))
    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        pysolver.sweep(model, cs[:10], client=client)          # workers get the model
        dask_t, _ = timed(lambda: pysolver.sweep(model, cs, client=client))
    n = len(cs)
    print(f"{n} cases of seed example 3 (penalty x initial position), 2-core machine")
    print(f"{'how':>34} {'cases/s':>8} {'vs hand loop':>12} {'vs serial':>9}")
    rows = [("hand-written loop (edit, load, run)", hand * n),
            ("model.run(params=case), warm", runs), ("sweep, in this process", serial),
            ("sweep, processes=2 (cold start)", cold), ("sweep, processes=2", warm),
            ("sweep, Dask LocalCluster 2 workers", dask_t),
            ("plain C program, one process", c_time),
            ("plain C program on 6 states", c6_time)]
    for name, t in rows:
        print(f"{name:>34} {n / t:8.0f} {hand * n / t:12.1f} {serial / t:9.2f}")
    print(f"\nsweep per case / warm model.run() of the same case: {serial / runs:.3f} "
          f"({serial / n * 1e6:.0f} us against {runs / n * 1e6:.0f} us; target <= 1.15)")
    print(f"warm model.run() / plain C program on the same cases: {runs / c_time:.2f} "
          f"({runs / n * 1e6:.0f} us against {c_time / n * 1e6:.0f} us; steps "
          f"{run_steps / n:.0f} against {c_steps / n:.0f} per case; target <= 1.3)")
    print(f"warm model.run() / the plain C program on 6 states: {runs / c6_time:.2f} "
          f"({c6_time / n * 1e6:.0f} us, {c6_steps / n:.0f} steps per case)")


if __name__ == "__main__":
    main()
