"""The sparse (CSC) Jacobian path: same matrix and same solution as the dense path."""

import numpy as np
import pytest

import pysolver

from helpers import TEST_DECKS
from scenes import chain_deck  # noqa: E402


@pytest.mark.parametrize("deck", [TEST_DECKS / "all_functions.xml", "chain"])
def test_csc_matches_dense(deck):
    model = pysolver.loads(chain_deck(12)) if deck == "chain" else pysolver.load(deck)
    k = model.compile().kernel
    rng = np.random.default_rng(3)
    y = k.layout.initial_state() + 0.01 * rng.normal(size=k.ny)
    yp = rng.normal(size=k.ny)
    dense = k.jacobian_array(0.1, y, yp, 5.0)
    sparse = k.jacobian_csc_array(0.1, y, yp, 5.0)
    np.testing.assert_array_equal(sparse.toarray(), dense)
    # the pattern holds every nonzero and is far from full for a chain
    assert np.all((dense != 0) <= (sparse.toarray() != 0) | (dense == 0))
    if deck == "chain":
        assert sparse.nnz < 0.2 * k.ny ** 2


def test_sparse_and_dense_runs_agree():
    model = pysolver.loads(chain_deck(10, end_time=0.3))
    # from C: the same driver and Newton test; only the linear solver differs
    a = model.run(linsolver="dense")
    b = model.run(linsolver="sparse")
    assert a.meta["options"]["linsolver"] == "dense" and b.meta["options"]["linsolver"] == "sparse"
    assert a.meta["options"]["backend"] == b.meta["options"]["backend"] == "c"
    assert a.success and b.success
    np.testing.assert_allclose(a.request(1), b.request(1), atol=1e-9)
    assert abs(a.stats["steps"] - b.stats["steps"]) <= 2
    # through scikit-sundae (IDA's own Newton coefficient on both sides)
    c = model.run(linsolver="dense", nonlin_conv_coef=0.33)
    d = model.run(linsolver="sparse", backend="sksundae")
    assert d.meta["options"]["backend"] == "sksundae" and d.success
    np.testing.assert_allclose(c.request(1), d.request(1), atol=1e-9)
    assert abs(c.stats["steps"] - d.stats["steps"]) <= 2


def _closed_chain(n):
    """chain_deck(n) with its free end tied back to its first mass: the Jacobian is no band."""
    text = chain_deck(n, end_time=0.02)
    tie = (f'<Force_Penalty id="{n + 1}" expr="DM({1000 + n - 1},1000) - {0.1 * (n - 1)}" '
           'penalty="1e3" penalty1="1"/>\n<Post_Request')
    return text.replace("<Post_Request", tie, 1)


@pytest.mark.parametrize("nx, nz", [(3, 2), (5, 3)])
def test_a_band_wider_than_the_matrix_runs_as_dense(nx, nz):
    """The particle bed without its LoadControl (36 and 90 states) has bandwidths (32, 35) and
    (86, 89): mu + ml passes n - 1, where SUNBandMatrix still stores mu + ml upper diagonals.
    The band solver gets the dense run's rows to within the tolerance (integr_tol 1e-5; the
    two LUs round differently); before stop 37 band storage was laid out for
    min(n - 1, mu + ml) and every such run failed at t = 0."""
    from helpers import DECKS
    text = (DECKS / "loadcontrol_bed.py").read_text().replace("END=0.6", "END=0.1")
    text = text[:text.index("LOADCONTROL(")] + text[text.index("REQUEST(1"):]
    model = pysolver.loads(text.replace("NX, NZ = 11, 5", f"NX, NZ = {nx}, {nz}"), fmt="py")
    mu, ml = model.compile().kernel.bandwidths()
    assert mu + ml > model.compile().kernel.ny - 1
    band = model.run(progress=False, linsolver="band", backend="c")
    dense = model.run(progress=False, linsolver="dense", backend="c")
    assert band.success and dense.success and band.meta["options"]["linsolver"] == "band"
    assert len(band.t) == len(dense.t)
    np.testing.assert_allclose(band.y, dense.y, rtol=0, atol=1e-5 * np.abs(dense.y).max())


def test_auto_picks_the_sparse_lu_for_large_scenes():
    """From 300 states the sparse LU from C, for a chain (a narrow band) and a closed chain
    (no band) alike; scikit-sundae's sparse solver on request; dense below."""
    from pysolver.options import SPARSE_THRESHOLD
    model = pysolver.loads(chain_deck(SPARSE_THRESHOLD // 6 + 1, end_time=0.02))
    res = model.run()
    assert (res.meta["options"]["linsolver"], res.meta["options"]["backend"]) == ("sparse", "c")
    res = model.run(backend="sksundae")
    assert res.success and res.meta["options"]["linsolver"] == "sparse"
    assert pysolver.loads(chain_deck(3, end_time=0.02)).run().meta["options"]["linsolver"] == "dense"
    closed = pysolver.loads(_closed_chain(SPARSE_THRESHOLD // 6 + 1))
    a = closed.run()
    assert a.success and (a.meta["options"]["linsolver"], a.meta["options"]["backend"]) == \
        ("sparse", "c")
    b = closed.run(linsolver="dense")
    np.testing.assert_allclose(a.y, b.y, atol=1e-9)
    assert abs(a.stats["steps"] - b.stats["steps"]) <= 2


def test_chain_constraint_and_pendulum_physics():
    res = pysolver.loads(chain_deck(5, penalty=1e6, penalty1=50, end_time=0.5)).run()
    assert res.success
    x, z = res.request(1)[:, 0], res.request(1)[:, 1]
    # link lengths hold to O(m g n / penalty): the end stays within the chain's reach
    assert np.all(np.hypot(x, z) <= 0.5 * (1 + 1e-3))
    # released horizontally, the free end falls below the pivot
    assert z[-1] < -0.2
