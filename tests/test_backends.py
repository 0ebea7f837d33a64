"""The two ways of running IDA give the same answers: from C (csrc/ida.c) and through
scikit-sundae's Python callbacks."""
import numpy as np
import pytest

import pysolver
from pysolver.solve import cida

pytestmark = pytest.mark.skipif(not cida.available(),
                                reason="the scikit-sundae wheel ships no SUNDIALS libraries")

DECKS = ["catenary_bead.xml", "particle_between_lines.xml", "torque_free_spin.xml",
         "sensor_output_interval.xml", "contact_onset_zero_crossing.xml", "static_seed3.xml"]


@pytest.mark.parametrize("name", DECKS)
def test_c_and_sksundae_backends_agree(decks, name):
    model = pysolver.load(decks / name)
    # scikit-sundae's IDA keeps its own Newton coefficient 0.33 and step growth 2
    c = model.run(backend="c", nonlin_conv_coef=0.33, max_step_growth=2)
    py = model.run(backend="sksundae")
    assert c.meta["options"]["backend"] == "c" and py.meta["options"]["backend"] == "sksundae"
    assert c.success and py.success
    np.testing.assert_array_equal(c.t, py.t)
    np.testing.assert_allclose(c.request(1), py.request(1), rtol=1e-9, atol=1e-12)
    assert c.stats["steps"] == py.stats["steps"]
    assert [e.sensor for e in c.events] == [e.sensor for e in py.events]
    # the C driver reports IDA's own failure counters
    assert c.stats["netf"] is not None and py.stats["netf"] is None


def test_backend_option_is_checked(decks):
    model = pysolver.load(decks / "catenary_bead.xml")
    with pytest.raises(ValueError, match="backend must be"):
        model.run(backend="fortran")
    with pytest.raises(ValueError, match="backend='c' needs"):
        model.run(backend="c", jacobian="dq")


def test_band_and_sparse_solvers_for_a_chain_match_scikit_sundaes():
    """A large chain has a narrow-band Jacobian: from C, IDA's band solver (filled from the
    kernel's triplets) and the sparse LU give the solution scikit-sundae's sparse solver
    gives, in the same steps."""
    from scenes import chain_deck
    model = pysolver.loads(chain_deck(60, end_time=0.1))
    k = model.compile().kernel
    mu, ml = k.bandwidths()
    assert 4 * (mu + ml + 1) <= k.ny
    ida = dict(backend="c", nonlin_conv_coef=0.33, max_step_growth=2)
    band = model.run(linsolver="band", **ida)
    lu = model.run(**ida)
    sparse = model.run(backend="sksundae")
    assert band.meta["options"]["linsolver"] == "band"
    assert lu.meta["options"]["linsolver"] == sparse.meta["options"]["linsolver"] == "sparse"
    for res in (band, lu):
        assert res.stats["steps"] == sparse.stats["steps"]
        assert np.nanmax(np.abs(res.request(1) - sparse.request(1))) < 1e-10
