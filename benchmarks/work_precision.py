"""Work-precision report: error against wall time over a tolerance sweep.

Problems with exact solutions (README "Accuracy and cost"):
- oscillator: bilateral penalty on a point mass under gravity (closed form);
- catenary: the seed bead, error against a pysolver run at integr_tol 1e-12.
Comparators run in the same process on the same equations: IDA with its own difference-quotient
Jacobian (``jacobian="dq"``), and SciPy's ``solve_ivp`` (Radau, BDF) on a hand-written NumPy
right-hand side, i.e. what a user would write without pysolver. Times are the minimum of
`repeat` runs after one warm-up (SciMLBenchmarks' convention); ratios are comparator / pysolver.

Run: ``python benchmarks/work_precision.py [--repeat 5] [--out DIR]``; besides the tables on
standard output it writes work_precision.csv, work_precision.md and a log-log PNG of error
against time (one line per solver) into benchmarks/out/.
"""
import argparse
import pathlib
import sys
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "benchmarks"))
import pysolver  # noqa: E402
from test_oscillator import DECK, exact, M, K, C, G  # noqa: E402


POINTS = []   # (problem, solver, tolerance, error, seconds) for the report files


def best_time(fn, repeat):
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def oscillator_rhs(t, s):
    z, v = s
    return [v, (-K * (z - 1) - C * v) / M - G]


def scipy_run(method, tol, t_eval, rhs, y0):
    from scipy.integrate import solve_ivp
    return solve_ivp(rhs, (t_eval[0], t_eval[-1]), y0, method=method, t_eval=t_eval,
                     rtol=tol, atol=tol)


def oscillator(repeat):
    model = pysolver.loads(DECK)
    rows = []
    for tol in (1e-4, 1e-6, 1e-8, 1e-10):
        tp, res = best_time(lambda: model.run(integr_tol=tol), repeat)
        z, _ = exact(res.t)
        err = np.abs(res.request(1)[:, 0] - z).max()
        tdq, rdq = best_time(lambda: model.run(integr_tol=tol, jacobian="dq"), repeat)
        edq = np.abs(rdq.request(1)[:, 0] - z).max()
        row = [tol, err, tp * 1e3, res.stats["steps"], edq, tdq / tp]
        POINTS.append(("oscillator", "pysolver", tol, err, tp))
        POINTS.append(("oscillator", "IDA + DQ Jacobian (scikit-sundae)", tol, edq, tdq))
        for method in ("Radau", "BDF", "LSODA"):
            ts, sol = best_time(lambda: scipy_run(method, tol, res.t, oscillator_rhs,
                                                  [1.2, 0.5]), repeat)
            e = np.abs(sol.y[0] - z).max()
            row += [e, ts / tp]
            POINTS.append(("oscillator", f"SciPy {method}", tol, e, ts))
        rows.append(row)
    print("\nDamped oscillator (t = 0..3, 301 outputs): max position error vs closed form")
    print(f"{'tol':>7} {'pysolver err':>12} {'ms':>7} {'steps':>6} | {'IDA-dq err':>10} "
          f"{'time x':>6} | {'Radau err':>10} {'time x':>6} | {'BDF err':>10} {'time x':>6} | "
          f"{'LSODA err':>10} {'time x':>6}")
    for r in rows:
        print(f"{r[0]:7.0e} {r[1]:12.2e} {r[2]:7.2f} {r[3]:6d} | {r[4]:10.2e} {r[5]:6.2f} | "
              f"{r[6]:10.2e} {r[7]:6.2f} | {r[8]:10.2e} {r[9]:6.2f} | {r[10]:10.2e} "
              f"{r[11]:6.2f}")
    return rows


def seed_decks(repeat):
    print("\nSeed decks at their own integr_tol: pysolver vs IDA with difference quotients")
    print(f"{'deck':>26} {'ms':>7} {'steps':>6} {'nres':>6} {'njac':>5} | {'dq ms':>7} "
          f"{'dq nres':>7} {'time x':>6}")
    for name in ("catenary_bead", "particle_above_line", "particle_between_lines",
                 "torque_free_spin", "spinning_top"):
        model = pysolver.load(ROOT / "decks" / f"{name}.xml")
        tp, res = best_time(model.run, repeat)
        tdq, rdq = best_time(lambda: model.run(jacobian="dq"), repeat)
        print(f"{name:>26} {tp * 1e3:7.2f} {res.stats['steps']:6d} {res.stats['nres']:6d} "
              f"{res.stats['njac']:5d} | {tdq * 1e3:7.2f} {rdq.stats['nres']:7d} {tdq / tp:6.2f}")


def seed3_comparators(repeat):
    """Seed example 3: pysolver against the same equations as a hand-written NumPy residual on
    the same scikit-sundae IDA (IDA's difference-quotient Jacobian), error in (x, z) at the
    outputs against a pysolver run at integr_tol 1e-12."""
    from sksundae.ida import IDA
    from comparators import initial_state, residual
    model = pysolver.load(ROOT / "decks" / "particle_between_lines.xml")
    ref = model.run(integr_tol=1e-12).request(1)[:, :2]
    print("\nSeed example 3 (x, z over 3 s, 601 outputs): pysolver vs a NumPy residual on IDA")
    print(f"{'tol':>7} {'pysolver err':>12} {'ms':>7} | {'NumPy+IDA err':>13} {'ms':>8} "
          f"{'time x':>6}")
    rows = []
    for tol in (1e-4, 1e-6, 1e-8):
        tp, res = best_time(lambda: model.run(integr_tol=tol), repeat)
        ep = np.abs(res.request(1)[:, :2] - ref).max()
        y0, yp0 = initial_state()

        def numpy_run():
            solver = IDA(residual, rtol=tol, atol=tol, max_num_steps=100000)
            return solver.solve(res.t, y0, yp0)

        tn, sol = best_time(numpy_run, repeat)
        en = np.abs(sol.y[:, :2] - ref).max()
        rows.append((tol, ep, tp, en, tn))
        POINTS.append(("seed example 3", "pysolver", tol, ep, tp))
        POINTS.append(("seed example 3", "NumPy residual + IDA (scikit-sundae)", tol, en, tn))
        print(f"{tol:7.0e} {ep:12.2e} {tp * 1e3:7.2f} | {en:13.2e} {tn * 1e3:8.2f} "
              f"{tn / tp:6.1f}")
    return rows


def plain_c_ida(tol, repeat):
    """Run benchmarks/c_ida/seed3_ida (built on first use): (steps, nres, njac, seconds, xz)."""
    import subprocess
    exe = ROOT / "benchmarks" / "c_ida" / "seed3_ida"
    if not exe.exists():
        subprocess.run(["bash", str(exe.parent / "build.sh")], check=True, capture_output=True)
    out = subprocess.run([str(exe), repr(tol), str(repeat)], check=True, capture_output=True,
                         text=True).stdout.split("\n")
    steps, nres, njac, sec = out[0].split()
    xz = np.array([[float(v) for v in line.split()] for line in out[1:] if line.strip()])
    return int(steps), int(nres), int(njac), float(sec), xz


def seed3_plain_c(repeat):
    """Seed example 3: pysolver against plain C IDA with a hand-written residual and Jacobian
    (the SUNDIALS 7.9 libraries of the scikit-sundae wheel), same output times and tolerance."""
    model = pysolver.load(ROOT / "decks" / "particle_between_lines.xml")
    ref = model.run(integr_tol=1e-12).request(1)[:, :2]
    print("\nSeed example 3: pysolver vs plain C IDA (hand-written residual and Jacobian)")
    print(f"{'tol':>7} {'pysolver err':>12} {'steps':>6} {'ms':>7} | {'C IDA err':>10} "
          f"{'steps':>6} {'ms':>7} | {'pysolver / C':>12}")
    rows = []
    for tol in (1e-4, 1e-6, 1e-8):
        tp, res = best_time(lambda: model.run(integr_tol=tol), repeat)
        steps, nres, njac, tc, xz = plain_c_ida(tol, max(repeat, 3))
        ep = np.abs(res.request(1)[:, :2] - ref).max()
        ec = np.abs(xz - ref).max()
        rows.append((tol, ep, tp, ec, tc))
        POINTS.append(("seed example 3", "plain C IDA, hand-written", tol, ec, tc))
        print(f"{tol:7.0e} {ep:12.2e} {res.stats['steps']:6d} {tp * 1e3:7.2f} | {ec:10.2e} "
              f"{steps:6d} {tc * 1e3:7.3f} | {tp / tc:12.1f}")
    return rows


def write_report(outdir):
    """Write work_precision.csv, work_precision.md and work_precision.png into outdir."""
    import csv
    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    with open(outdir / "work_precision.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["problem", "solver", "tolerance", "max_error", "seconds"])
        w.writerows(POINTS)
    with open(outdir / "work_precision.md", "w") as fh:
        fh.write("| problem | solver | tolerance | max error | ms |\n|---|---|---|---|---|\n")
        for p, name, tol, err, sec in POINTS:
            fh.write(f"| {p} | {name} | {tol:.0e} | {err:.2e} | {sec * 1e3:.3f} |\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    problems = sorted({p[0] for p in POINTS})
    fig, axes = plt.subplots(1, len(problems), figsize=(6 * len(problems), 4.5), squeeze=False)
    for ax, prob in zip(axes[0], problems):
        for name in sorted({p[1] for p in POINTS if p[0] == prob}):
            pts = sorted((p[3], p[4]) for p in POINTS if p[0] == prob and p[1] == name)
            ax.loglog([e for e, _ in pts], [t * 1e3 for _, t in pts], "o-", label=name)
        ax.set_xlabel("max error")
        ax.set_ylabel("wall time, ms (best of runs)")
        ax.set_title(prob)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(outdir / "work_precision.png", dpi=110)
    print(f"\nwrote {outdir / 'work_precision.csv'}, .md and .png")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "out"),
                        help="folder for work_precision.csv/.md/.png")
    args = parser.parse_args()
    oscillator(args.repeat)
    seed_decks(args.repeat)
    seed3_comparators(args.repeat)
    seed3_plain_c(args.repeat)
    write_report(args.out)


if __name__ == "__main__":
    main()
