"""Work-precision for exact joints: pysolver against Exudyn, in one process.

Wall time against error on two joint decks.

Problems (decks in decks/joints/, references in benchmarks/data/joint_references.json,
written by benchmarks/joint_references.py):
- pendulum_revolute: 1 kg body 2 m from a REVOLUTE pivot, released horizontally, 5 s; error
  = max over the 101 reference times of the centre-of-mass position error (DX, DY of the cm,
  Post_Request 1 channels 0, 1) against the closed form.
- iftomm_a02_fourbar: IFToMM A02, N = 40 (81 links, 121 REVOLUTEs), 20 s; error = max over
  the 401 reference times of the B0 position error (DX(22), DY(22), Post_Request 1 channels
  0, 1) against the exact parallelogram branch.

pysolver runs ``Model.run(integr_tol=tol)`` over decades of tolerance (IDA, variable order
and step); A02 at 1e-11 runs once more under a budget of 60,000 steps (``max_num_steps``)
and is reported as what it is (finished, or how far it got). Exudyn runs generalized-alpha (index
3) at fixed steps h, built by ``exudyn_pendulum`` and ``exudyn_a02`` of
benchmarks/joint_references.py (the models of README-joints.md's comparator table). Times are
wall seconds in this process: for pysolver all of ``Model.run`` after a first run that
compiles the kernel and is not timed, for Exudyn ``SolveDynamic`` only (its model building is
not timed); the pendulum is the best of `repeat` runs on both sides, A02 one run per point.
A failed run is reported as failed, never as a time. The headline takes each Exudyn point and
the fastest pysolver run whose error is at most Exudyn's, and gives the ratio Exudyn time /
pysolver time.

Run from the checkout root: ``python benchmarks/joints.py [--quick] [--repeat 5] [--out
PATH]``. The full mode takes a few minutes on this 2-core machine (the A02 runs at 1e-10
and 1e-11 dominate); ``--quick`` (about 15 s) runs the pendulum at three tolerances, A02
at integr_tol 1e-6 only (over its full 20 s) and Exudyn at h = 1e-3 only. Writes
benchmarks/data/joints_work_precision.json (every number, the machine, the versions and the
commit pysolver was imported from) and prints the tables. No timing is asserted.
"""
import argparse
import json
import math
import os
import pathlib
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))

import joint_references as jr  # noqa: E402 - benchmarks/ is put on the path just above
import provenance  # noqa: E402 - benchmarks/ is on the path

import pysolver  # noqa: E402

PYSOLVER_ROOT = pathlib.Path(pysolver.__file__).resolve().parent.parent
DECKS = ROOT / "decks" / "joints"
OUT = HERE / "data" / "joints_work_precision.json"

#: integr_tol values and Exudyn steps h, full mode / --quick
PEND_TOLS = ((1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10), (1e-4, 1e-7, 1e-10))
PEND_H = ((1e-2, 1e-3, 2e-4, 1e-4), (1e-3,))
#: A02's error is not monotone in the tolerance (the phase near the separatrix), so the full
#: mode adds half decades where Exudyn's errors fall, for the equal-error comparison
A02_TOLS = ((1e-4, 1e-5, 1e-6, 1e-7, 3e-8, 2e-8, 1e-8, 5e-9, 3e-9, 1e-9, 1e-10), (1e-6,))
#: A02 at 1e-11 (full mode only) runs with this step budget and reports how far it gets: the
#: tightest tolerance is where the joints' compliance (docs/numerics.md, "Constraints") ends
A02_PROBE = (1e-11, 60000)
A02_H = ((2.5e-3, 1e-3, 5e-4), (1e-3,))


def reference(problem, xkey, ykey):
    """Times and (x, y) of one problem of benchmarks/data/joint_references.json."""
    ref = json.loads((HERE / "data" / "joint_references.json").read_text())
    table = ref["problems"][problem]
    return np.array(table["times"]), np.array(table[xkey]), np.array(table[ykey])


def position_error(res, times, x, y):
    """|(channel 0, channel 1) of Post_Request 1 - (x, y)| at the reference times the run
    reached (an empty array if none)."""
    keep = times <= (res.t[-1] + 1e-9 if len(res.t) else -np.inf)
    times, x, y = times[keep], x[keep], y[keep]
    if not len(times):
        return np.zeros(0)
    q = res.request(1)
    rows = np.searchsorted(res.t, times - 1e-12)
    if not np.allclose(res.t[rows], times, atol=1e-12):
        raise RuntimeError("the run's output times are not the reference's")
    return np.hypot(q[rows, 0] - x, q[rows, 1] - y)


def timed_run(model, tol, repeat, **options):
    """Best wall time of `repeat` runs of model.run(integr_tol=tol) and the last result."""
    best, res = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = model.run(integr_tol=tol, **options)
        best = min(best, time.perf_counter() - t0)
    return best, res


def pysolver_row(model, tol, repeat, ref, **options):
    """Steps, wall (None if the run failed), max error (up to the failure if it failed)."""
    wall, res = timed_run(model, tol, repeat, **options)
    dist = position_error(res, *ref)
    err = float(dist.max()) if len(dist) else None
    row = dict(method="pysolver", integr_tol=tol, options=options,
               steps=int(res.stats["steps"]), nres=int(res.stats["nres"]),
               njac=int(res.stats["njac"]), nfail=int(res.stats["nfail"]),
               wall_s=wall if res.success else None, wall_s_until_failure=None
               if res.success else wall, max_err_m=err if res.success else None,
               max_err_m_until_failure=None if res.success else err,
               end_err_m=float(dist[-1]) if res.success else None,
               success=bool(res.success), message=res.message,
               reached_t=float(res.t[-1]) if len(res.t) else None,
               load_1min=os.getloadavg()[0])
    print(f"  pysolver tol {tol:.0e}{' ' + str(options) if options else ''}: "
          f"{provenance.fmt_row(row)}", flush=True)
    return row


def pysolver_sweep(deck, tols, repeat, ref, probe=None):
    """One row per tolerance, and one for `probe` = (tol, max_num_steps) if given. The first
    run (at the loosest tolerance) compiles the kernel and is not timed."""
    model = pysolver.load(deck)
    t0 = time.perf_counter()
    warm = model.run(integr_tol=max(tols))
    warm_s = time.perf_counter() - t0
    rows = [pysolver_row(model, tol, repeat, ref) for tol in tols]
    if probe:
        rows.append(pysolver_row(model, probe[0], 1, ref, max_num_steps=probe[1]))
    return rows, dict(integr_tol=max(tols), wall_s_including_compile=warm_s,
                      success=bool(warm.success), timing=provenance.plain(warm.timing))


def exudyn_pendulum_sweep(hs, repeat):
    rows = []
    for h in hs:
        r = jr.exudyn_pendulum(h, repeat=repeat)
        rows.append(dict(method="Exudyn", h=h, steps=r["steps"], wall_s=r["wall_s"],
                         max_err_m=r["max_err_m"], end_err_m=r["end_err_m"], success=True,
                         message="", load_1min=os.getloadavg()[0]))
        print(f"  Exudyn h {h:.1e}: {provenance.fmt_row(rows[-1])}", flush=True)
    return rows


def exudyn_a02_sweep(hs):
    rows = []
    for h in hs:
        r = jr.exudyn_a02(h)
        ok = r["completed"]
        rows.append(dict(method="Exudyn", h=h, steps=r["steps"], linear_solver=r["linear_solver"],
                         wall_s=r["wall_s"] if ok else None,
                         max_err_m=r["max_err_m"] if ok else None,
                         max_err_m_until_failure=None if ok else r["max_err_m"],
                         end_err_m=r["end_err_m"],
                         success=ok, message=r["message"], reached_t=r["reached_t"],
                         load_1min=os.getloadavg()[0]))
        print(f"  Exudyn h {h:.1e}: {provenance.fmt_row(rows[-1])}", flush=True)
    return rows


def headline(py_rows, ex_rows):
    """Each Exudyn point matched with the fastest pysolver run at equal or smaller error."""
    return provenance.headline(py_rows, ex_rows)


def print_table(title, rows):
    print(f"\n{title}")
    print(f"{'method':>9} {'setting':>14} {'steps':>9} {'wall s':>9} {'max error m':>12}")
    for r in rows:
        setting = (f"tol {r['integr_tol']:.0e}" if r["method"] == "pysolver"
                   else f"h {r['h']:.1e}")
        if r.get("options"):
            setting += "*"
        wall = "failed" if r["wall_s"] is None else f"{r['wall_s']:.4f}"
        err = "-" if r["max_err_m"] is None else f"{r['max_err_m']:.2e}"
        print(f"{r['method']:>9} {setting:>14} {r['steps']:>9,} {wall:>9} {err:>12}")
        if r.get("options"):
            print(f"{'':>10}* with {r['options']}")
        if not r["success"]:
            print(f"{'':>10}failed: {r['message']} (reached t = {r.get('reached_t')}, "
                  f"error until then {r.get('max_err_m_until_failure')})")


def print_headline(title, lines):
    print(f"\n{title}: fastest pysolver run at equal or smaller error than each Exudyn point")
    for h in lines:
        ex = (f"Exudyn h {h['exudyn_h']:.1e}: {h['exudyn_wall_s']:.4f} s, "
              f"{h['exudyn_max_err_m']:.2e} m")
        if h["ratio"] is None:
            print(f"  {ex}; no pysolver run reaches that error")
        else:
            print(f"  {ex}; pysolver tol {h['pysolver_integr_tol']:.0e}: "
                  f"{h['pysolver_wall_s']:.4f} s, {h['pysolver_max_err_m']:.2e} m -> "
                  f"{provenance.speed(h['ratio'])}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="pendulum at 3 tolerances, A02 at 1e-6, Exudyn at h = 1e-3 only")
    ap.add_argument("--repeat", type=int, default=None,
                    help="pendulum runs per point, best taken (default 5, --quick 3)")
    ap.add_argument("--out", default=str(OUT))
    args = ap.parse_args(argv)
    q = int(args.quick)
    repeat = args.repeat or (3 if args.quick else 5)
    out = dict(generated_by="benchmarks/joints.py" + (" --quick" if args.quick else ""),
               machine=provenance.machine(pysolver, PYSOLVER_ROOT),
               method=("one process; pysolver: first run (compiles the kernel) untimed, then "
                       f"pendulum best of {repeat} runs, A02 one run per tolerance; Exudyn: "
                       f"generalized-alpha fixed step, pendulum best of {repeat} SolveDynamic "
                       "calls, A02 one call; wall seconds; errors in metres against "
                       "benchmarks/data/joint_references.json"),
               problems={})
    t_start = time.perf_counter()

    print("pendulum_revolute (5 s): centre-of-mass position error", flush=True)
    ref = reference("pendulum_revolute", "x", "y")
    py, warm = pysolver_sweep(DECKS / "pendulum_revolute.xml", PEND_TOLS[q], repeat, ref)
    ex = exudyn_pendulum_sweep(PEND_H[q], repeat)
    out["problems"]["pendulum_revolute"] = dict(pysolver=py, exudyn=ex, warmup=warm,
                                                headline=headline(py, ex))
    provenance.save(out, args.out)                    # so far, in case the run is stopped

    print("iftomm_a02_fourbar (N = 40, 20 s): B0 position error", flush=True)
    ref = reference("iftomm_a02_fourbar", "B0_x", "B0_y")
    py, warm = pysolver_sweep(DECKS / "iftomm_a02_fourbar.xml", A02_TOLS[q], 1, ref,
                              probe=None if args.quick else A02_PROBE)
    out["problems"]["iftomm_a02_fourbar"] = dict(pysolver=py, warmup=warm)
    provenance.save(out, args.out)
    ex = exudyn_a02_sweep(A02_H[q])
    out["problems"]["iftomm_a02_fourbar"] = dict(pysolver=py, exudyn=ex, warmup=warm,
                                                 headline=headline(py, ex))

    for name, prob in out["problems"].items():
        print_table(name, prob["pysolver"] + prob["exudyn"])
        print_headline(name, prob["headline"])
    provenance.finish(out, args.out, t_start, PYSOLVER_ROOT)


if __name__ == "__main__":
    main()
