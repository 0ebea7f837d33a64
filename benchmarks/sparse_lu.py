"""The sparse LU (csrc/sparselu.c) against SUNDIALS' SuperLU_MT, in one process.

Each scene runs with ``linsolver="sparse"`` (pysolver's LU) and ``linsolver="superlu_mt"``
(SuperLU_MT on one thread, what the C driver used before), alternating, best of `repeat`
warm runs each; both go through the same IDA from C, so only the factorizations and solves
differ. Scenes: IFToMM A02 (N = 40, exact joints, in 3-D: 2,023 states) over its first 5 s at
integr_tol 1e-6, 1e-8 and 1e-9, and the LoadControl particle bed (53 particles, penalty
contacts, 325 states). Prints time per run, steps, Jacobian evaluations (each one
factorization) and the ratio SuperLU_MT time / LU time; the answers of the two are compared
too (the largest difference of request channels), since a faster wrong answer is no answer.
The LU counts its replays; the driver does not report them, so they are not printed.

Run from the checkout root: ``python benchmarks/sparse_lu.py [--quick] [--repeat 3]``.
No timing is asserted.
"""
import argparse
import pathlib
import re
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

import pysolver  # noqa: E402


def _a02(end):
    """A02 in 3-D (PYSOLVER_PLANAR=off while it compiles): the large sparse DAE this
    benchmark measures (as a planar scene A02 has 970 unknowns, docs/numerics.md)."""
    import os
    text = (ROOT / "decks" / "joints" / "iftomm_a02_fourbar.xml").read_text()
    model = pysolver.loads(re.sub(r'end_time="[^"]*"', f'end_time="{end}"', text))
    before = os.environ.get("PYSOLVER_PLANAR")
    os.environ["PYSOLVER_PLANAR"] = "off"
    try:
        model.compile()
    finally:
        if before is None:
            del os.environ["PYSOLVER_PLANAR"]
        else:
            os.environ["PYSOLVER_PLANAR"] = before
    return model


def _bed():
    return pysolver.load(ROOT / "decks" / "loadcontrol_bed.py")


def measure(model, repeat, **opts):
    """{solver: (best wall s, Result)} for the two sparse solvers, alternating."""
    best = {}
    for solver in ("sparse", "superlu_mt"):
        model.run(linsolver=solver, **opts)                # warm: kernel and plans built
    for _ in range(repeat):
        for solver in ("sparse", "superlu_mt"):
            t0 = time.perf_counter()
            res = model.run(linsolver=solver, **opts)
            wall = time.perf_counter() - t0
            if solver not in best or wall < best[solver][0]:
                best[solver] = (wall, res)
    return best


def report(name, best):
    lu, slu = best["sparse"], best["superlu_mt"]
    ok = lu[1].success and slu[1].success
    diff = np.nanmax(np.abs(lu[1].request(1) - slu[1].request(1))) if ok else float("nan")
    for solver, (wall, res) in best.items():
        st = res.stats
        print(f"| {name} | {solver} | {res.success} | {st['steps']} | {st['njac']} | "
              f"{wall:.3f} | {wall / max(st['steps'], 1) * 1e6:.0f} |")
    print(f"| {name} | ratio SuperLU_MT / LU | | | | **{slu[0] / lu[0]:.2f}x** | "
          f"largest channel difference {diff:.1e} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="A02 over 1 s at 1e-6, bed once")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    repeat = 1 if args.quick else args.repeat
    print("| scene | solver | success | steps | Jacobians | wall s | us/step |")
    print("|---|---|---|---|---|---|---|")
    a02 = _a02(1.0 if args.quick else 5.0)
    for tol in (1e-6,) if args.quick else (1e-6, 1e-8, 1e-9):
        report(f"A02 N=40 integr_tol {tol:g}", measure(a02, repeat, integr_tol=tol))
    if not args.quick:
        report("particle bed, 53", measure(_bed(), repeat))


if __name__ == "__main__":
    main()
