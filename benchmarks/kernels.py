"""Generated C kernels against the tape interpreter and against plain C (issue 14).

1. Seed example 3 at equal error against ``benchmarks/c_ida/seed3_ida`` (plain C IDA with a
   hand-written residual and Jacobian on the same SUNDIALS build): both programs run over
   integr_tol 1e-4 .. 1e-8 in half decades; each pysolver point's time is divided by the C
   program's time at the same error, interpolated log-log on C's error-time curve. Reported: the
   ratio per tolerance, its median and worst, for the generated kernel and for the tapes;
   against the C program's 4 states (x z vx vz: the fewest the problem needs) and, for the
   generated kernel, against the same program on 6 (x y z vx vy vz: the equations pysolver
   integrates for a point body, whose y carries no force).
2. Before / after: the oscillator, the rigid body, the stiff penalty pendulum and the seed decks,
   each run with ``kernel="tapes"`` and with the generated kernel (time ratio, same answers).
3. The particle bed (53 and 195 particles) through the C driver's sparse path, on each kernel,
   against scikit-sundae's Python callbacks: time per step, steps, answers.

Run: ``python benchmarks/kernels.py [--repeat 7]`` (OPENBLAS_NUM_THREADS=1 for steady times).
"""
import argparse
import pathlib

import numpy as np

import pysolver

from scenes import OSCILLATOR, PENDULUM

ROOT = pathlib.Path(__file__).resolve().parent.parent
TOLS = [float(10.0 ** e) for e in np.arange(-4.0, -8.01, -0.5)]


def best_time(fn, repeat):
    """(minimum wall time of `repeat` calls after a warm-up, the last result)."""
    import time
    fn()
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def c_curve(ref, repeat, ny=4):
    """Plain C IDA on seed example 3 at every tolerance, on `ny` states: (errors, seconds), by
    tolerance."""
    from work_precision import plain_c_ida
    errs, secs = [], []
    for tol in TOLS:
        _, _, _, sec, xz = plain_c_ida(tol, max(repeat, 3), ny)
        errs.append(np.abs(xz - ref).max())
        secs.append(sec)
    return np.array(errs), np.array(secs)


def at_equal_error(err, errs, secs):
    """The C program's time at error `err`, interpolated log-log on its error-time curve
    (clamped to the curve's ends), and whether `err` lies inside the curve."""
    order = np.argsort(errs)
    le, lt = np.log(errs[order]), np.log(secs[order])
    inside = le[0] <= np.log(err) <= le[-1]
    return float(np.exp(np.interp(np.log(err), le, lt))), bool(inside)


def seed3_equal_error(repeat, kinds=("generated", "tapes")):
    """Print and return {kind: [(tol, error, seconds, C seconds at that error, ratio)]}."""
    model = pysolver.load(ROOT / "decks" / "particle_between_lines.xml")
    ref = model.run(integr_tol=1e-12).request(1)[:, :2]
    errs, secs = c_curve(ref, repeat)
    out = {}
    print("\nSeed example 3 at equal error: pysolver time / plain C IDA time at the same "
          "error (log-log interpolation on C's curve)")
    print(f"{'tol':>7} {'C err':>9} {'C ms':>7} | " + " | ".join(
        f"{k + ' err':>13} {'ms':>6} {'ratio':>5}" for k in kinds))
    for kind in kinds:
        rows = []
        for tol in TOLS:
            sec, res = best_time(lambda: model.run(integr_tol=tol, kernel=kind), repeat)
            assert res.meta["kernel"] == kind
            err = np.abs(res.request(1)[:, :2] - ref).max()
            tc, inside = at_equal_error(err, errs, secs)
            rows.append((tol, err, sec, tc, sec / tc, inside))
        out[kind] = rows
    for i, tol in enumerate(TOLS):
        cols = [f"{out[k][i][1]:13.2e} {out[k][i][2] * 1e3:6.3f} {out[k][i][4]:5.2f}"
                + ("" if out[k][i][5] else "*") for k in kinds]
        print(f"{tol:7.0e} {errs[i]:9.2e} {secs[i] * 1e3:7.3f} | " + " | ".join(cols))
    for kind in kinds:
        ratios = [r[4] for r in out[kind]]
        print(f"{kind:>10}: median ratio {np.median(ratios):.2f}, worst {max(ratios):.2f}")
    if "generated" in out:
        errs6, secs6 = c_curve(ref, repeat, ny=6)
        ratios6 = [r[2] / at_equal_error(r[1], errs6, secs6)[0] for r in out["generated"]]
        print(f"generated against the C program on 6 states: median ratio "
              f"{np.median(ratios6):.2f}, worst {max(ratios6):.2f} (per tolerance: "
              + ", ".join(f"{x:.2f}" for x in ratios6) + ")")
    print("(* outside C's error range: its time at the nearest end)")
    return out


def before_after(repeat):
    """The tapes' time over the generated kernel's, same tolerance, and the largest difference
    between their answers."""
    scenes = [("oscillator", pysolver.loads(OSCILLATOR), (1e-4, 1e-6, 1e-8, 1e-10)),
              ("rigid body", pysolver.load(ROOT / "decks" / "torque_free_spin.xml"),
               (1e-4, 1e-6, 1e-8, 1e-10)),
              ("stiff penalty pendulum", pysolver.loads(PENDULUM), (1e-6, 1e-8, 1e-10))]
    scenes += [(name, pysolver.load(ROOT / "decks" / f"{name}.xml"), (None,))
               for name in ("catenary_bead", "particle_above_line", "particle_between_lines",
                            "spinning_top")]
    print("\nBefore / after: the tapes against the generated kernel, same tolerance")
    print(f"{'scene':>24} {'tol':>7} {'tapes ms':>9} {'generated ms':>12} {'speed-up':>8} "
          f"{'steps':>11} {'max |dy|':>9}")
    rows = []
    for name, model, tols in scenes:
        for tol in tols:
            over = {} if tol is None else {"integr_tol": tol}
            tt, rt = best_time(lambda: model.run(kernel="tapes", **over), repeat)
            tg, rg = best_time(lambda: model.run(kernel="generated", **over), repeat)
            n = min(len(rt.t), len(rg.t))
            dy = np.abs(rt.y[:n] - rg.y[:n]).max()
            rows.append((name, tol, tt, tg))
            label = "deck" if tol is None else f"{tol:.0e}"
            print(f"{name:>24} {label:>7} {tt * 1e3:9.3f} {tg * 1e3:12.3f} {tt / tg:8.2f} "
                  f"{rt.stats['steps']:5d}/{rg.stats['steps']:<5d} {dy:9.1e}")
    return rows


def bed(sizes=((11, 5), (20, 10))):
    """The LoadControl particle bed (decks/loadcontrol_bed.py, unilateral contacts between
    particles and with the floor): the C driver's sparse path (SuperLU_MT) on each kernel
    against scikit-sundae's Python callbacks (SciPy's SuperLU); time per step, steps, and the
    largest difference of the final state from the first configuration."""
    import time
    text = (ROOT / "decks" / "loadcontrol_bed.py").read_text()
    configs = [("C sparse, generated", dict(backend="c", kernel="generated")),
               ("C sparse, tapes", dict(backend="c", kernel="tapes")),
               ("scikit-sundae, generated", dict(backend="sksundae", kernel="generated"))]
    print("\nParticle bed: C driver's sparse path against scikit-sundae's callbacks")
    print(f"{'particles':>9} {'states':>6} {'path':>26} {'kernel':>9} {'steps':>6} "
          f"{'us/step':>8} {'s':>6} {'max |dy| end':>12}")
    rows = []
    for nx, nz in sizes:
        model = pysolver.loads(text.replace("NX, NZ = 11, 5", f"NX, NZ = {nx}, {nz}"), fmt="py")
        first = None
        for label, over in configs:
            model.run(**over)                       # warm: compile and cache outside the timing
            t0 = time.perf_counter()
            res = model.run(**over)
            sec = time.perf_counter() - t0
            first = res.y[-1] if first is None else first
            dy = np.abs(res.y[-1] - first).max()
            rows.append((nx * nz - nz // 2, label, res.stats["steps"], sec))
            print(f"{nx * nz - nz // 2:9d} {len(first):6d} {label:>26} {res.meta['kernel']:>9} "
                  f"{res.stats['steps']:6d} {1e6 * sec / res.stats['steps']:8.1f} {sec:6.2f} "
                  f"{dy:12.1e}")
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    seed3_equal_error(args.repeat)
    before_after(args.repeat)
    bed()


if __name__ == "__main__":
    main()
