"""pytest-benchmark timings: load + compile, and whole runs next to a comparator in the same
process.

Run: ``pytest benchmarks --benchmark-enable --benchmark-group-by=func``.
Groups compare pysolver's exact Jacobian with IDA's difference-quotient Jacobian on the same
residual, dense with sparse solvers on chains, and pysolver's step control with IDA's own on
stiff penalties; ``work_precision.py`` adds error-against-time sweeps and the SciPy, NumPy,
plain C and Exudyn comparators.
"""
import pathlib

import pytest

import pysolver

ROOT = pathlib.Path(__file__).resolve().parent.parent
import andrews  # noqa: E402
from scenes import PENDULUM, USERSUB_FORMS, chain_deck  # noqa: E402

DECKS = ["catenary_bead", "particle_above_line", "particle_between_lines", "torque_free_spin",
         "spinning_top"]

#: IDA as SUNDIALS ships it, for the step-control comparisons
IDA_AS_SHIPPED = {"max_step_growth": 2, "nonlin_conv_coef": 0.33}


@pytest.mark.parametrize("deck", DECKS)
def test_load_and_compile(benchmark, deck):
    """Parse, validate and compile a deck into its C kernel (no integration)."""
    def load():
        model = pysolver.load(ROOT / "decks" / f"{deck}.xml")
        return model.compile().kernel
    kernel = benchmark(load)
    benchmark.extra_info["states"] = kernel.ny


@pytest.mark.parametrize("jacobian", ["exact", "dq"])
@pytest.mark.parametrize("deck", DECKS)
def test_seed_deck(benchmark, deck, jacobian):
    model = pysolver.load(ROOT / "decks" / f"{deck}.xml")
    res = benchmark(model.run, jacobian=jacobian)
    assert res.success
    benchmark.extra_info.update(res.stats)


@pytest.mark.parametrize("linsolver", ["dense", "sparse"])
@pytest.mark.parametrize("n", [20, 100])
def test_chain(benchmark, n, linsolver):
    model = pysolver.loads(chain_deck(n, end_time=0.3))
    res = benchmark(model.run, linsolver=linsolver)
    assert res.success
    benchmark.extra_info.update(res.stats)


@pytest.mark.parametrize("n", [10, 100, 1000, 5000])
def test_chain_scaling(benchmark, n):
    """The scaling scene (benchmarks/scaling.py): load + compile timed, then 0.2 s of
    integration with the solver chosen from the structure (dense at N = 10, band from C
    above), its time per step in extra_info."""
    text = chain_deck(n, end_time=0.2)

    def load():
        model = pysolver.loads(text)
        model.compile()
        return model
    model = benchmark.pedantic(load, rounds=3, iterations=1)   # timed: load + compile
    res = model.run()
    assert res.success
    benchmark.extra_info.update(res.stats, states=model.compile().kernel.ny,
                                integrate_s=res.timing["integrate"],
                                ms_per_step=1e3 * res.timing["integrate"] / res.stats["steps"],
                                linsolver=res.meta["options"]["linsolver"])


@pytest.fixture(scope="module")
def seed3_c_curve():
    """Seed example 3's reference answer and plain C IDA's error-time curve (kernels.py)."""
    import kernels
    model = pysolver.load(ROOT / "decks" / "particle_between_lines.xml")
    ref = model.run(integr_tol=1e-12).request(1)[:, :2]
    return model, ref, kernels.c_curve(ref, 5)


@pytest.mark.parametrize("kernel", ["generated", "tapes"])
@pytest.mark.parametrize("tol", [1e-4, 1e-6, 1e-8])
def test_seed3_against_plain_c(benchmark, seed3_c_curve, tol, kernel):
    """Seed example 3 on each kernel; extra_info holds the error and the ratio to plain C IDA
    at the same error (benchmarks/kernels.py has the whole sweep, median and worst)."""
    import kernels
    model, ref, (errs, secs) = seed3_c_curve
    res = benchmark(model.run, integr_tol=tol, kernel=kernel)
    assert res.success and res.meta["kernel"] == kernel
    err = float(abs(res.request(1)[:, :2] - ref).max())
    c_sec, inside = kernels.at_equal_error(err, errs, secs)
    benchmark.extra_info.update(error=err, c_seconds_at_error=c_sec, inside_c_range=inside)
    if benchmark.stats:                 # None with --benchmark-disable (the tests' default)
        benchmark.extra_info["ratio_to_c"] = benchmark.stats.stats.min / c_sec


# at 1e9 IDA's own step control fails its error test almost every step (minutes per run)
@pytest.mark.parametrize("penalty,control", [(1e8, "pysolver"), (1e8, "IDA as shipped"),
                                             (1e9, "pysolver"), (1e10, "pysolver")])
def test_andrews(benchmark, penalty, control):
    """Andrews' mechanism with its revolute joints as penalties."""
    model = pysolver.loads(andrews.deck(penalty))
    opts = {} if control == "pysolver" else IDA_AS_SHIPPED
    res = benchmark.pedantic(model.run, kwargs=opts, rounds=3, iterations=1)
    assert res.success
    benchmark.extra_info.update(res.stats, error=andrews.error(res))


@pytest.mark.parametrize("control", ["pysolver", "IDA as shipped"])
def test_stiff_pendulum(benchmark, control):
    """Penalty pendulum k = 1e8, c = 2e4 over 10 s at integr_tol 1e-8."""
    model = pysolver.loads(PENDULUM)
    opts = {} if control == "pysolver" else IDA_AS_SHIPPED
    res = benchmark.pedantic(model.run, kwargs=dict(opts, integr_tol=1e-8), rounds=3,
                             iterations=1)
    assert res.success
    benchmark.extra_info.update(res.stats)


@pytest.mark.parametrize("form", USERSUB_FORMS)
def test_usersub_lines(benchmark, tmp_path, form):
    """Seed example 3 with its penalties as user subroutines in each form; compare each with
    the expression group member (``benchmarks/usersubs.py`` prints the ratios)."""
    from scenes import lines_deck
    text, fmt = lines_deck(form, tmp_path)
    if text is None:
        pytest.skip("no C compiler for the subroutine library")
    model = pysolver.loads(text, fmt=fmt)
    res = benchmark(model.run)
    assert res.success
    benchmark.extra_info.update(steps=res.stats["steps"])


@pytest.mark.parametrize("writer", ["c", "csv_module"])
def test_csv_writer(benchmark, tmp_path, writer):
    """100,000 rows of 6 random numbers: the C writer (Result.save) against the csv module
    writing the same text (repr of each float), the writer before it."""
    import csv

    import numpy as np

    from pysolver.results import _write_csv
    data = np.random.default_rng(0).standard_normal((100_000, 6))
    names = [f"c{i}" for i in range(6)]
    path = tmp_path / "out.csv"

    def python_writer():
        with open(path, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(names)
            for row in data:
                w.writerow([repr(float(v)) for v in row])
    benchmark(python_writer if writer == "csv_module" else lambda: _write_csv(path, names, data))
