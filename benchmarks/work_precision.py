"""Work-precision report: error against wall time over a tolerance sweep.

Problems (README "Accuracy and cost"):
- oscillator: bilateral penalty on a point mass under gravity, against its closed form;
- seed example 3 (particle between two lines), against a pysolver run at integr_tol 1e-12;
- a rigid body (torque-free precession), against its closed form;
- stiff penalty pendulum (k = 1e8, c = 2e4, 10 s), against the rigid pendulum.
Comparators run on the same equations: IDA with its own difference-quotient Jacobian
(``jacobian="dq"``); SciPy's ``solve_ivp`` (Radau, BDF, LSODA) and scikit-sundae's IDA on
hand-written NumPy functions, i.e. what a user would write without pysolver; plain C IDA with
hand-written residual and Jacobian (benchmarks/c_ida, built on first use); Exudyn's
generalized-alpha at fixed steps when ``exudyn`` is installed (``pip install .[bench]``).
Times are the minimum of `repeat` runs after one warm-up (SciMLBenchmarks' convention);
ratios are comparator / pysolver.

Run: ``python benchmarks/work_precision.py [--repeat 5] [--out DIR]``; besides the tables on
standard output it writes work_precision.csv, work_precision.md and a log-log PNG of error
against time (one line per solver) into benchmarks/out/.
"""
import argparse
import os
import pathlib
import subprocess
import sys
import time

import numpy as np

import pysolver

import kernels
from scenes import OSCILLATOR as DECK
from scenes import PENDULUM, C, G, K, M
from scenes import oscillator_exact as exact

ROOT = pathlib.Path(__file__).resolve().parent.parent


#: (problem, solver, tolerance or step, max error, final error, L2 error, seconds)
POINTS = []


def record(problem, solver, tol, dist, seconds):
    """Keep one point of the report from the error at every output (a distance >= 0); return
    its largest value. L2 is the root mean square over the outputs (SciMLBenchmarks)."""
    dist = np.asarray(dist, float)
    POINTS.append((problem, solver, tol, dist.max(), dist[-1], np.sqrt(np.mean(dist ** 2)),
                   seconds))
    return dist.max()


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


def oscillator_exudyn(repeat):
    """Exudyn's generalized-alpha on the oscillator at fixed steps (if installed)."""
    from test_oscillator import V0, Z0

    import exudyn_models
    if not exudyn_models.available():
        print("\nExudyn not installed (pip install .[bench]): its lines are left out")
        return []
    print("\nDamped oscillator in Exudyn (generalized-alpha, spectral radius 0.8)")
    print(f"{'h':>7} {'max error':>10} {'ms':>8}")
    rows = []
    for h in (1e-2, 3e-3, 1e-3, 3e-4, 1e-4):
        t, pos, sec = exudyn_models.oscillator(h, M, K, C, G, Z0, V0, repeat=max(repeat, 1))
        err = record("oscillator", "Exudyn, generalized-alpha", h,
                     np.abs(pos[:, 1] - exact(t)[0]), sec)
        rows.append((h, err, sec))
        print(f"{h:7.0e} {err:10.2e} {sec * 1e3:8.3f}")
    return rows


def oscillator(repeat):
    model = pysolver.loads(DECK)
    rows = []
    for tol in (1e-4, 1e-6, 1e-8, 1e-10):
        tp, res = best_time(lambda: model.run(integr_tol=tol), repeat)
        z, _ = exact(res.t)
        err = record("oscillator", "pysolver", tol, np.abs(res.request(1)[:, 0] - z), tp)
        tdq, rdq = best_time(lambda: model.run(integr_tol=tol, jacobian="dq"), repeat)
        edq = record("oscillator", "IDA + DQ Jacobian (scikit-sundae)", tol,
                     np.abs(rdq.request(1)[:, 0] - z), tdq)
        row = [tol, err, tp * 1e3, res.stats["steps"], edq, tdq / tp]
        for method in ("Radau", "BDF", "LSODA"):
            ts, sol = best_time(lambda: scipy_run(method, tol, res.t, oscillator_rhs,
                                                  [1.2, 0.5]), repeat)
            e = record("oscillator", f"SciPy {method}", tol, np.abs(sol.y[0] - z), ts)
            row += [e, ts / tp]
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
    outputs against a pysolver run at integr_tol 1e-12. Returns rows (tol, pysolver error,
    seconds, steps, reference) for :func:`seed3_plain_c`."""
    from sksundae.ida import IDA

    from comparators import initial_state, residual, rhs
    model = pysolver.load(ROOT / "decks" / "particle_between_lines.xml")
    ref = model.run(integr_tol=1e-12).request(1)[:, :2]
    print("\nSeed example 3 (x, z over 3 s, 601 outputs): pysolver vs a NumPy residual on IDA")
    print(f"{'tol':>7} {'pysolver err':>12} {'ms':>7} | {'NumPy+IDA err':>13} {'ms':>8} "
          f"{'time x':>6} | SciPy on the same NumPy equations (error, time ratio)")
    rows = []
    for tol in (1e-4, 1e-6, 1e-8):
        tp, res = best_time(lambda: model.run(integr_tol=tol), repeat)
        ep = record("seed example 3", "pysolver", tol,
                    np.abs(res.request(1)[:, :2] - ref).max(axis=1), tp)
        y0, yp0 = initial_state()

        def numpy_run():
            solver = IDA(residual, rtol=tol, atol=tol, max_num_steps=100000)
            return solver.solve(res.t, y0, yp0)

        tn, sol = best_time(numpy_run, repeat)
        en = record("seed example 3", "NumPy residual + IDA (scikit-sundae)", tol,
                    np.abs(sol.y[:, :2] - ref).max(axis=1), tn)
        rows.append((tol, ep, tp, res.stats["steps"], ref))
        scipy_cols = []
        for method in ("Radau", "BDF", "LSODA"):
            ts, sp = best_time(lambda: scipy_run(method, tol, res.t, rhs, y0), repeat)
            es = record("seed example 3", f"SciPy {method}", tol,
                        np.abs(sp.y[:2].T - ref).max(axis=1), ts)
            scipy_cols.append(f"{method} {es:.2e} {ts / tp:5.1f}x")
        print(f"{tol:7.0e} {ep:12.2e} {tp * 1e3:7.2f} | {en:13.2e} {tn * 1e3:8.2f} "
              f"{tn / tp:6.1f} | " + " | ".join(scipy_cols))
    return rows


def build_c_programs(folder):
    """Build the plain C programs of `folder` (benchmarks/c_ida) with its build.sh, against
    the scikit-sundae of the interpreter running this (not whatever python3 is on PATH); a
    RuntimeError with the build's own output when it fails."""
    done = subprocess.run(["bash", str(folder / "build.sh")], capture_output=True, text=True,
                          env=dict(os.environ, PYTHON=sys.executable))
    if done.returncode:
        raise RuntimeError(f"building the plain C programs ({folder / 'build.sh'}, with "
                           f"PYTHON={sys.executable}) failed with exit status "
                           f"{done.returncode}:\n{(done.stderr or done.stdout).strip()}")


def c_program(name, *args):
    """Run benchmarks/c_ida/NAME ARGS (built on first use): (first output line's numbers,
    the remaining lines as an array)."""
    exe = ROOT / "benchmarks" / "c_ida" / name
    if not exe.exists():
        build_c_programs(exe.parent)
    out = subprocess.run([str(exe), *map(str, args)], check=True, capture_output=True,
                         text=True).stdout.split("\n")
    rows = np.array([[float(v) for v in line.split()] for line in out[1:] if line.strip()])
    return [float(v) for v in out[0].split()], rows


def plain_c_ida(tol, repeat, ny=4):
    """Seed example 3 in plain C: (steps, nres, njac, seconds, xz); `ny` 4 states (x z vx vz)
    or 6 (the particle's three coordinates, as pysolver integrates a point body)."""
    (steps, nres, njac, sec), xz = c_program("seed3_ida", repr(tol), repeat, "", ny)
    return int(steps), int(nres), int(njac), sec, xz


def seed3_plain_c(pysolver_rows, repeat):
    """Seed example 3: the pysolver runs of :func:`seed3_comparators` against plain C IDA with
    a hand-written residual and Jacobian (the SUNDIALS 7.9 libraries of the scikit-sundae
    wheel), same output times and tolerance."""
    print("\nSeed example 3: pysolver vs plain C IDA (hand-written residual and Jacobian)")
    print(f"{'tol':>7} {'pysolver err':>12} {'steps':>6} {'ms':>7} | {'C IDA err':>10} "
          f"{'steps':>6} {'ms':>7} | {'pysolver / C':>12}")
    for tol, ep, tp, psteps, ref in pysolver_rows:
        steps, _, _, tc, xz = plain_c_ida(tol, max(repeat, 3))
        ec = record("seed example 3", "plain C IDA, hand-written", tol,
                    np.abs(xz - ref).max(axis=1), tc)
        print(f"{tol:7.0e} {ep:12.2e} {psteps:6d} {tp * 1e3:7.2f} | {ec:10.2e} "
              f"{steps:6d} {tc * 1e3:7.3f} | {tp / tc:12.1f}")


def rigid_body(repeat):
    """Torque-free precession of an axisymmetric rigid body (decks/torque_free_spin.xml): body
    angular velocity against the closed form; IDA with difference quotients on the same
    residual, and SciPy on Euler's equations with Euler-parameter kinematics in NumPy."""
    i1, i3, w3, w1 = 0.1, 0.18, 20.0, 1.0
    om = (i3 - i1) / i1 * w3
    model = pysolver.load(ROOT / "decks" / "torque_free_spin.xml")

    def exact_err(t, w):
        return np.hypot(w[:, 0] - w1 * np.cos(om * t), w[:, 1] - w1 * np.sin(om * t))

    def euler_rhs(t, s):
        wx, wy, wz, e0, e1, e2, e3 = s
        return [(i1 - i3) / i1 * wy * wz, (i3 - i1) / i1 * wx * wz, 0.0,
                0.5 * (-e1 * wx - e2 * wy - e3 * wz), 0.5 * (e0 * wx - e3 * wy + e2 * wz),
                0.5 * (e3 * wx + e0 * wy - e1 * wz), 0.5 * (-e2 * wx + e1 * wy + e0 * wz)]

    y0 = model.run(integr_tol=1e-4).y[0]
    s0 = [w1, 0.0, w3, *y0[3:7]]
    print("\nTorque-free rigid body (2 s, 201 outputs): body angular velocity vs closed form")
    print(f"{'tol':>7} {'pysolver err':>12} {'ms':>7} | {'IDA-dq err':>10} {'time x':>6} | "
          "SciPy Radau, BDF, LSODA (error, time ratio)")
    for tol in (1e-4, 1e-6, 1e-8, 1e-10):
        tp, res = best_time(lambda: model.run(integr_tol=tol), repeat)
        ep = record("rigid body", "pysolver", tol, exact_err(res.t, res.request(1)), tp)
        tdq, rdq = best_time(lambda: model.run(integr_tol=tol, jacobian="dq"), repeat)
        edq = record("rigid body", "IDA + DQ Jacobian (scikit-sundae)", tol,
                     exact_err(rdq.t, rdq.request(1)), tdq)
        cols = []
        for method in ("Radau", "BDF", "LSODA"):
            ts, sp = best_time(lambda: scipy_run(method, tol, res.t, euler_rhs, s0), repeat)
            es = record("rigid body", f"SciPy {method}", tol, exact_err(sp.t, sp.y[:2].T), ts)
            cols.append(f"{es:.2e} {ts / tp:5.1f}x")
        print(f"{tol:7.0e} {ep:12.2e} {tp * 1e3:7.2f} | {edq:10.2e} {tdq / tp:6.2f} | "
              + " | ".join(cols))


def pendulum_error(t, xy):
    """Largest distance from the rigid pendulum released horizontally (the penalty model itself
    differs from it by about 6e-6 at k = 1e8)."""
    from scipy.integrate import solve_ivp
    sol = solve_ivp(lambda _, s: [s[1], -9.81 * np.cos(s[0])], (0, t[-1]), [0, 0], t_eval=t,
                    rtol=1e-13, atol=1e-13, method="DOP853")
    return np.hypot(xy[:, 0] - np.cos(sol.y[0]), xy[:, 1] - np.sin(sol.y[0]))


def stiff_pendulum(repeat):
    """Issue 5's stiff penalty pendulum: pysolver (its C driver limits the step growth once
    IDA's error test keeps failing) and IDA as shipped, plain C IDA with and without the same
    step control, and Exudyn at fixed steps."""
    import exudyn_models
    model = pysolver.loads(PENDULUM)
    shipped = dict(max_step_growth=2, nonlin_conv_coef=0.33)
    print("\nStiff penalty pendulum (k = 1e8, c = 2e4, 10 s): max distance from the rigid one")
    print(f"{'solver':>34} {'tol / h':>8} {'error':>9} {'steps':>7} {'njac':>7} {'ms':>8}")

    def line(name, tol, dist, steps, njac, sec):
        err = record("stiff penalty pendulum", name, tol, dist, sec)
        print(f"{name:>34} {tol:8.1e} {err:9.2e} {steps:7d} {njac:7d} {sec * 1e3:8.2f}")

    for tol in (1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
        sec, res = best_time(lambda: model.run(integr_tol=tol), repeat)
        line("pysolver", tol, pendulum_error(res.t, res.request(1)), res.stats["steps"],
             res.stats["njac"], sec)
    for tol in (1e-6, 1e-7, 1e-8):
        sec, res = best_time(lambda: model.run(integr_tol=tol, **shipped), 1)
        line("pysolver, IDA's step control", tol, pendulum_error(res.t, res.request(1)),
             res.stats["steps"], res.stats["njac"], sec)
    for label, eta, nlconv, tols in (("plain C IDA, as shipped", 0, 0, (1e-6, 1e-7, 1e-8)),
                                     ("plain C IDA, pysolver's control", 1.1, 0.033,
                                      (1e-6, 1e-7, 1e-8, 1e-9, 1e-10))):
        for tol in tols:
            (steps, _, njac, _, _, sec), xy = c_program("pendulum_ida", repr(tol), 1e8, 2e4,
                                                        eta, nlconv, max(repeat, 3))
            line(label, tol, pendulum_error(np.linspace(0, 10, 1001), xy), int(steps),
                 int(njac), sec)
    if not exudyn_models.available():
        print("Exudyn not installed (pip install .[bench]): its lines are left out")
        return
    for h in (2e-3, 1e-3, 5e-4, 2.5e-4):
        t, xy, sec = exudyn_models.pendulum(1e8, 2e4, h, repeat=max(repeat, 1))
        line("Exudyn, generalized-alpha", h, pendulum_error(t, xy), int(round(10 / h)), 0, sec)


def write_report(outdir):
    """Write work_precision.csv, work_precision.md and work_precision.png into outdir. The
    tolerance column is integr_tol, or the fixed step for Exudyn."""
    import csv
    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    with open(outdir / "work_precision.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["problem", "solver", "tolerance", "max_error", "final_error", "l2_error",
                    "seconds"])
        w.writerows(POINTS)
    with open(outdir / "work_precision.md", "w") as fh:
        fh.write("| problem | solver | tolerance / step | max error | final error | L2 error "
                 "| ms |\n|---|---|---|---|---|---|---|\n")
        for p, name, tol, emax, efin, el2, sec in POINTS:
            fh.write(f"| {p} | {name} | {tol:.1e} | {emax:.2e} | {efin:.2e} | {el2:.2e} "
                     f"| {sec * 1e3:.3f} |\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    problems = list(dict.fromkeys(p[0] for p in POINTS))
    fig, axes = plt.subplots(1, len(problems), figsize=(5.5 * len(problems), 4.5),
                             squeeze=False)
    for ax, prob in zip(axes[0], problems):
        for name in dict.fromkeys(p[1] for p in POINTS if p[0] == prob):
            pts = sorted((p[3], p[6]) for p in POINTS if p[0] == prob and p[1] == name)
            ax.loglog([e for e, _ in pts], [t * 1e3 for _, t in pts], "o-", label=name)
        ax.set_xlabel("max error")
        ax.set_ylabel("wall time, ms (best of runs)")
        ax.set_title(prob)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
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
    oscillator_exudyn(args.repeat)
    seed_decks(args.repeat)
    seed3_plain_c(seed3_comparators(args.repeat), args.repeat)
    kernels.seed3_equal_error(args.repeat)
    kernels.before_after(args.repeat)
    rigid_body(args.repeat)
    stiff_pendulum(args.repeat)
    write_report(args.out)


if __name__ == "__main__":
    main()
