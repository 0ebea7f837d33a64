"""Batch-study throughput: 1000 cases of seed example 3 (penalty of line 1 x initial x of the
particle, a 40 x 25 grid), cases per second

- by the hand-written loop (edit the deck text, load, run) on 100 of the cases,
- by pysolver.sweep in this process (processes=0), with 2 worker processes (the first sweep
  starts the worker server; the second reuses it) and on a 2-worker Dask LocalCluster,

and the per-case overhead of a sweep beyond the integration itself (a sweep case in this
process against model.run() of the same model).

Run: ``python benchmarks/sweep.py``.
"""
import time

import numpy as np

import pysolver

from scenes import DECKS

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


def main():
    cs = cases()
    model = pysolver.load(DECK)
    model.run()
    bare, _ = timed(lambda: [model.run(progress=False) for _ in range(200)])
    bare /= 200
    hand, _ = timed(lambda: hand_loop(cs[:100]))
    hand /= 100
    serial, sw = timed(lambda: pysolver.sweep(model, cs, processes=0))
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
    rows = [("hand-written loop (edit, load, run)", hand * n), ("sweep, in this process", serial),
            ("sweep, processes=2 (cold start)", cold), ("sweep, processes=2", warm),
            ("sweep, Dask LocalCluster 2 workers", dask_t)]
    for name, t in rows:
        print(f"{name:>34} {n / t:8.0f} {hand * n / t:12.1f} {serial / t:9.2f}")
    print(f"\nper-case overhead beyond the run itself: {(serial / n - bare) * 1e6:.0f} us "
          f"({100 * (serial / n - bare) / bare:.1f} % of a {bare * 1e3:.2f} ms run)")


if __name__ == "__main__":
    main()
