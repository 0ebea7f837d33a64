"""User subroutine paths against the expression version: seed example 3 with both penalties as
a traced Python script, a traced Python function, a Python function with a state-dependent branch
(traced into IF), an untraceable Python function through NumPy (called from the kernel through
cffi) and a C library, each of the last two also giving its partials (py_syspar / c_syspar),
and the C library giving its partial in time as well (c_syspar "TIME"), at several tolerances;
time ratios to the expression version (best of `repeat` runs in this process), steps, the cost
of one call, and the least ratio the NumPy routine could have: its own body, timed alone with
free data access, times its calls per run.

Run: ``python benchmarks/usersubs.py [--repeat 5]``.
"""
import argparse
import pathlib
import tempfile
import time
import timeit

import numpy as np

import pysolver

from scenes import LINES_NUMPY_SYSPAR, USERSUB_FORMS, lines_deck


def best(fn, repeat):
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def forms(repeat, tols=(1e-4, 1e-6, 1e-8)):
    folder = tempfile.mkdtemp()
    models = {}
    for form in USERSUB_FORMS:
        text, fmt = lines_deck(form, folder)
        if text is not None:
            models[form] = pysolver.loads(text, fmt=fmt)
    print("Seed example 3, each penalty a user subroutine: time / expression version's time")
    print(f"{'integr_tol':>10} {'form':>18} {'ms':>8} {'ratio':>6} {'steps':>6} {'max diff':>9}")
    rows = []
    for tol in tols:
        ref = models["expression"].run(integr_tol=tol)
        t_ref = best(lambda: models["expression"].run(integr_tol=tol), repeat)
        for form, model in models.items():
            res = model.run(integr_tol=tol)
            t = best(lambda: model.run(integr_tol=tol), repeat)
            diff = np.abs(res.request(1)[:, :2] - ref.request(1)[:, :2]).max()
            rows.append((tol, form, t / t_ref))
            print(f"{tol:10.0e} {form:>18} {t * 1e3:8.3f} {t / t_ref:6.2f} "
                  f"{res.stats['steps']:6d} {diff:9.1e}")
    return models, rows


#: Routine calls per residual of each form the kernel calls (both routines): the value, a
#: forward and a backward step in each input the routine reads, one forward step in each it
#: does not (C: TDISP gives DX, DY, DZ, and time; NumPy form: DX and DZ; its time argument is
#: never read, which its bytecode shows, so it is not stepped in time); the forms that give
#: their partials (c_syspar / py_syspar): the value, and for C the step in time unless it
#: gives that partial too (c_syspar_time).
CALLS_PER_RESIDUAL = {"untraceable": 2 * 5, "untraceable_syspar": 2 * 1, "c": 2 * 7,
                      "c_syspar": 2 * 2, "c_syspar_time": 2 * 1}


def call_cost(models, repeat):
    """One residual of the untraceable and C forms against the expression version's, each at a
    new time (the kernel reuses a routine's values at an unchanged state)."""
    print("\nCost of one routine call from the kernel (residual time difference / calls)")
    y = models["expression"].compile().kernel.layout.initial_state()
    yp = np.zeros_like(y)
    base = models["expression"].compile().kernel
    n = 2000
    times = [1e-3 * i / n for i in range(n)]
    t_ref = best(lambda: [base.residual_array(t, y, yp) for t in times], repeat) / n
    for form, calls in CALLS_PER_RESIDUAL.items():
        if form not in models:
            continue
        k = models[form].compile().kernel
        t = best(lambda: [k.residual_array(t, y, yp) for t in times], repeat) / n
        print(f"{form:>18}: {(t - t_ref) / calls * 1e6:6.2f} us per call "
              f"(residual {t * 1e6:.1f} us, expression version {t_ref * 1e6:.1f} us)")


def python_floor(repeat, tol=1e-6):
    """The least time ratio any kernel could give the NumPy routine with py_syspar: its body
    alone (py_sysfnc and py_syspar answering at no cost) times its calls per run, over the
    expression version's time; and the same routine's measured ratio."""
    folder = pathlib.Path(tempfile.mkdtemp())
    text, fmt = lines_deck("script", folder)
    # the script form with the NumPy routine, counting its calls
    (folder / "lines.py").write_text("CALLS = [0]\n\n\n" + LINES_NUMPY_SYSPAR.replace(
        "    import numpy as np\n", "    import numpy as np\n    CALLS[0] += 1\n", 1))
    model = pysolver.loads(text, fmt=fmt)
    counter = next(iter(model.compile().model._scripts.values()))["CALLS"]
    t_run = best(lambda: model.run(integr_tol=tol), repeat)
    counter[0] = 0
    model.run(integr_tol=tol)
    calls = counter[0]
    expression = pysolver.loads(lines_deck("expression", folder)[0], fmt="py")
    t_ref = best(lambda: expression.run(integr_tol=tol), repeat)
    scope = {"py_sysfnc": lambda fnc, ids: [1.0, 0], "py_syspar": lambda fnc, ids, p: 0}
    exec(LINES_NUMPY_SYSPAR, scope)
    body = min(timeit.repeat(lambda: scope["PFOSUB"](2, 0.1, [10.0, 1.0], 2, 0, 0),
                             number=20000, repeat=repeat)) / 20000
    print(f"\nNumPy routine with py_syspar at integr_tol {tol:.0e}: {calls} calls per run; its "
          f"body alone {body * 1e6:.2f} us per call")
    print(f"  least ratio (body x calls / expression version): {calls * body / t_ref:.1f}; "
          f"measured: {t_run / t_ref:.1f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    models, _ = forms(args.repeat)
    call_cost(models, args.repeat)
    python_floor(args.repeat)


if __name__ == "__main__":
    main()
