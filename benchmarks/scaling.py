"""Scaling: a chain of N point masses linked by bilateral distance penalties.

Run: ``python benchmarks/scaling.py [N ...]`` (default 10 100 300 1000). Prints, per N, the
states, the linear solver chosen, steps, time per step and per residual, the Jacobian's
nonzeros, the compile time, and the process's peak resident memory after the run, and the
exponent of a power-law fit of time per step against N.
"""
import resource
import sys
import time

import numpy as np

import pysolver  # noqa: E402

from scenes import chain_deck  # noqa: E402


def main(sizes):
    print(f"{'N':>6} {'states':>7} {'solver':>7} {'compile s':>9} {'steps':>6} "
          f"{'ms/step':>8} {'us/res':>7} {'nnz':>8} {'peak MB':>8}")
    rows = []
    for n in sizes:
        t0 = time.perf_counter()
        model = pysolver.loads(chain_deck(n, end_time=0.2))
        kernel = model.compile().kernel
        t_compile = time.perf_counter() - t0
        res = model.run()
        assert res.success, res.message
        per_step = res.timing["integrate"] / res.stats["steps"]
        nnz = kernel.sparsity().nnz
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        rows.append((n, per_step))
        print(f"{n:6d} {kernel.ny:7d} {res.meta['options']['linsolver']:>7} {t_compile:9.3f} "
              f"{res.stats['steps']:6d} {per_step * 1e3:8.3f} "
              f"{res.timing['integrate'] / res.stats['nres'] * 1e6:7.1f} {nnz:8d} {peak:8.1f}")
    if len(rows) >= 2:
        n, t = np.array(rows).T
        slope = np.polyfit(np.log(n), np.log(t), 1)[0]
        print(f"time per step ~ N^{slope:.2f} over N = {int(n[0])}..{int(n[-1])}")


if __name__ == "__main__":
    main([int(a) for a in sys.argv[1:]] or [10, 100, 300, 1000])
