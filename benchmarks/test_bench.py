"""pytest-benchmark timings of whole runs, each next to a comparator in the same process.

Run: ``pytest benchmarks --benchmark-enable --benchmark-group-by=func``.
Groups compare pysolver's exact Jacobian with IDA's difference-quotient Jacobian on the same
residual; ``work_precision.py`` adds error-against-time sweeps and SciPy comparators.
"""
import pathlib
import sys

import pytest

import pysolver

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from scenes import chain_deck  # noqa: E402

DECKS = ["catenary_bead", "particle_above_line", "particle_between_lines", "torque_free_spin",
         "spinning_top"]


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
