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
def test_c_and_sksundae_backends_agree(decks, name, monkeypatch):
    # the same equations on both: scikit-sundae integrates every state, so C does too here
    # (tests/test_held.py compares held states with all of them)
    monkeypatch.setenv("PYSOLVER_HELD", "off")
    model = pysolver.load(decks / name)
    # scikit-sundae's IDA keeps its own Newton coefficient 0.33 and step growth 2, and
    # factors with SUNDIALS' dense solver
    c = model.run(backend="c", nonlin_conv_coef=0.33, max_step_growth=2,
                  linsolver="sundials_dense")
    py = model.run(backend="sksundae")
    assert c.meta["options"]["backend"] == "c" and py.meta["options"]["backend"] == "sksundae"
    assert c.meta["options"]["linsolver"] == "sundials_dense"
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


@pytest.mark.parametrize("name", ["catenary_bead.xml", "particle_between_lines.xml",
                                  "torque_free_spin.xml", "spinning_top.xml",
                                  "stiff_penalty_pendulum.xml", "joints/pendulum_revolute.xml",
                                  "joints/spherical_pendulum.xml"])
def test_dense_lu_is_as_accurate_as_sundials_dense(decks, name):
    """Dense scenes are factored by pysolver's own LU on the C driver (csrc/ida.c
    dense_setup: SUNDIALS' pivots and operations, a multiplication by each pivot's reciprocal
    where SUNDIALS divides). Its solves differ from SUNDIALS' at rounding level, which a run
    may carry into other steps, so each run is checked against one at 1e-12: the
    differential states within 3x the other's error either way, in at most 1.2x its steps.
    (A joint's reactions, which IDA's error test leaves out, are as accurate as the last
    Newton iterate: 1.4e-5 and 3.3e-4 at 1e-9 on the spherical pendulum, one per solver.)"""
    model = pysolver.load(decks / name)
    diff = np.asarray(model.compile().kernel.arrays["state_alg"]) == 0
    fine = model.run(integr_tol=1e-12, linsolver="sundials_dense")
    own, ref = (model.run(integr_tol=1e-9, linsolver=ls) for ls in ("auto", "sundials_dense"))
    assert own.meta["options"]["linsolver"] == "dense"
    assert ref.meta["options"]["linsolver"] == "sundials_dense"
    assert own.success and ref.success
    err_own, err_ref = (np.nanmax(np.abs(r.y - fine.y)[:, diff]) for r in (own, ref))
    assert err_own <= 3 * err_ref + 1e-12 and err_ref <= 3 * err_own + 1e-12
    assert own.stats["steps"] <= 1.2 * ref.stats["steps"]
    assert ref.stats["steps"] <= 1.2 * own.stats["steps"]


@pytest.mark.parametrize("name, tol", [("torque_free_spin.xml", 1e-9),
                                       ("driven_indenter.xml", 1e-9),
                                       ("loadcontrol_indenter.xml", 1e-6)])
def test_small_dense_scenes_solve_with_the_inverse_to_rounding(decks, name, tol):
    """Scenes of at most 16 states solve with the inverse of IDA's matrix from its second
    solve on (csrc/ida.c, dense_solve). On smooth runs, with no chaos to carry rounding into
    other steps, that gives SUNDIALS' dense solver's answers to rounding (measured 4e-17 to
    2e-15 of the largest state) in its steps."""
    model = pysolver.load(decks / name)
    assert model.compile().kernel.ny <= 16
    own, ref = (model.run(integr_tol=tol, linsolver=ls) for ls in ("auto", "sundials_dense"))
    assert own.meta["options"]["linsolver"] == "dense" and own.success and ref.success
    assert own.stats["steps"] == ref.stats["steps"]
    assert np.abs(own.y - ref.y).max() <= 1e-12 * np.abs(ref.y).max()


def _inverse_solves(model, **options):
    """(solves by the inverse in a warm run of `model`, the run's residuals)."""
    from pysolver.build.bindings import lib
    model.run(**options)
    (_, fast), = model.compile().batched.values()
    before = lib.ps_ida_inverse_solves(fast.solver.s)
    res = model.run(**options)
    assert res.success
    return lib.ps_ida_inverse_solves(fast.solver.s) - before, res.stats["nres"]


def test_the_inverse_solves_only_well_conditioned_small_systems(decks):
    """Seed example 3 (4 integrated states; condition numbers median 3e4) solves most Newton
    iterations by the inverse: all but each factorization's first and those of condition above
    1e8 (766 of 899 measured). SUNDIALS' own solver makes none; the penalty pendulum at
    k = 1e10, whose matrices' condition numbers reach 1e9-1e10 once the rod carries the mass,
    almost none (51 of 11,672 measured: the first steps): with the inverse there its runs took
    more steps (docs/numerics.md, "The dense solve")."""
    from test_hard_cases import pendulum_deck
    seed3 = pysolver.load(decks / "particle_between_lines.xml")
    n, nres = _inverse_solves(seed3)
    assert 0.75 * nres < n < nres
    assert _inverse_solves(seed3, linsolver="sundials_dense")[0] == 0
    n, nres = _inverse_solves(pysolver.loads(pendulum_deck(1e10)), integr_tol=1e-8)
    assert n < 0.01 * nres
