"""Static and quasi-static figures: iterations, accuracy and FIM_D against FIM_S.

Run: ``python benchmarks/statics.py``. Times are the best of 5 runs after a warm-up.
"""
import pathlib
import time

import numpy as np

import pysolver

from scenes import rest_penetration

ROOT = pathlib.Path(__file__).resolve().parent.parent


def best(fn, n=5):
    fn()
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def deck(name, **rep):
    text = (ROOT / "decks" / name).read_text()
    for a, b in rep.items():
        text = text.replace(a, b)
    return pysolver.loads(text)


def main():
    print("Static solves")
    print(f"{'deck':>22} {'method':>8} {'answer':>36} {'iter':>5} {'imbalance':>10} {'ms':>7}")
    g = rest_penetration(1e4, 9.81, 1.0)
    for name, method, what in [("static_seed3.xml", "FIM_S", "z - z_exact"),
                               ("static_seed3.xml", "MKEAM", "z - z_exact"),
                               ("static_pendulum.xml", "FIM_S", "z_cm (upright 0.5)"),
                               ("static_pendulum.xml", "MKEAM", "z_cm (hanging -0.5)")]:
        model = deck(name, **{'method="FIM_S"': f'method="{method}"'})
        t, res = best(model.run)
        st = res.statics[0]
        val = (res.request(1)[0, 1] - (1 - g)) if "seed3" in name else res.request(1)[0, 2]
        print(f"{name:>22} {method:>8} {what + ' = ' + format(val, '.3e'):>36} "
              f"{st.iterations:5d} {st.imbalance:10.1e} {t * 1e3:7.2f}")
    print("\nQuasi-static stack of 5 particles, 101 outputs: FIM_D against FIM_S at every output")
    fd = deck("quasi_static_stack.xml")
    fs = deck("quasi_static_stack.xml", **{'method="FIM_D"': 'method="FIM_S"'})
    td, rd = best(fd.run)
    ts, rs = best(fs.run)
    diff = np.abs(rd.request(1)[:, :5] - rs.request(1)[:, :5]).max()
    print(f"  FIM_D {td * 1e3:.2f} ms ({rd.stats['nres']} residuals, {rd.stats['njac']} "
          f"Jacobians); FIM_S {ts * 1e3:.2f} ms ({rs.stats['nres']}, {rs.stats['njac']}); "
          f"FIM_D is {ts / td:.2f}x faster; largest difference {diff:.1e} m")


if __name__ == "__main__":
    main()
