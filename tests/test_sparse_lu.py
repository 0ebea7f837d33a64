"""csrc/sparselu.c: the sparse LU that factors IDA's iteration matrices on the C driver,
against dense solves on the matrices it meets (mass-like diagonals, constraint rows with no
diagonal) and on the cases that must not go quietly wrong (stale pivots, singular matrices)."""
import numpy as np
import pytest
import scipy.sparse as sp

import pysolver
from pysolver.build.bindings import ffi, lib

from helpers import DECKS


class LU:
    """ps_lu_* on one scipy CSC pattern, in a column order (None: natural)."""

    def __init__(self, pattern, order=None):
        pattern = sp.csc_matrix(pattern)
        pattern.sort_indices()
        self.n = pattern.shape[0]
        self.colptr = np.ascontiguousarray(pattern.indptr, np.int32)
        self.rowind = np.ascontiguousarray(pattern.indices, np.int32)
        self.order = None if order is None else np.ascontiguousarray(order, np.int32)
        fb = ffi.from_buffer
        self.f = ffi.gc(lib.ps_lu_new(self.n, ffi.cast("int *", fb(self.colptr)),
                                      ffi.cast("int *", fb(self.rowind)),
                                      ffi.NULL if order is None else
                                      ffi.cast("int *", fb(self.order))), lib.ps_lu_free)

    def _values(self, matrix):
        matrix = sp.csc_matrix(matrix)
        matrix.sort_indices()
        assert np.array_equal(matrix.indptr, self.colptr)
        assert np.array_equal(matrix.indices, self.rowind)
        self.keep = np.ascontiguousarray(matrix.data, float)
        return ffi.cast("double *", ffi.from_buffer(self.keep))

    def factor(self, matrix):
        return lib.ps_lu_factor(self.f, self._values(matrix))

    def refactor(self, matrix):
        return lib.ps_lu_refactor(self.f, self._values(matrix))

    def solve(self, b):
        x = np.array(b, dtype=float)
        lib.ps_lu_solve(self.f, ffi.cast("double *", ffi.from_buffer(x)))
        return x

    def counts(self):
        out = ffi.new("long[3]")
        lib.ps_lu_counts(self.f, out)
        return list(out)


def _saddle(n, m, seed):
    """A matrix shaped like an iteration matrix with constraints: a mass-like diagonal block
    with couplings, constraint gradients G and G^T, and a zero block where the multipliers
    meet (entries kept in the pattern, values zero)."""
    rng = np.random.default_rng(seed)
    M = sp.diags(rng.uniform(1.0, 3.0, n)) + sp.random(n, n, density=0.02, random_state=seed)
    G = sp.random(m, n, density=0.15, random_state=seed + 1, data_rvs=rng.standard_normal)
    G = G + sp.csr_matrix((np.ones(m), (np.arange(m), rng.choice(n, m, replace=False))),
                          shape=(m, n))
    K = sp.bmat([[M, G.T], [G, None]]).tocsc()
    zero_diag = sp.csc_matrix((np.full(n + m, 1e-300), (np.arange(n + m), np.arange(n + m))))
    K = (K + zero_diag).tocsc()
    K.data[K.data == 1e-300] = 0.0
    return K


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("ordered", [False, True])
def test_solves_equal_dense_solves(seed, ordered):
    """Random sparse systems and saddle-point systems (no usable diagonal in the constraint
    rows), natural and COLAMD order: residual at rounding level, the same x as LAPACK's."""
    import scipy.sparse.linalg as spl
    rng = np.random.default_rng(seed)
    general = sp.random(120, 120, density=0.04, random_state=seed) + sp.eye(120)
    for A in (general.tocsc(), _saddle(90, 30, seed)):
        order = np.argsort(spl.splu(A.tocsc(), permc_spec="COLAMD").perm_c) if ordered else None
        lu = LU(A, order)
        assert lu.factor(A) == 0
        b = rng.standard_normal(A.shape[0])
        x = lu.solve(b)
        dense = np.linalg.solve(A.toarray(), b)
        assert np.abs(x - dense).max() <= 1e-10 * np.abs(dense).max()
        assert np.abs(A @ x - b).max() <= 1e-12 * (abs(A).max() * np.abs(x).max())


def test_a_replay_solves_new_values_with_the_old_pivots():
    """IDA's next matrix has the same pattern and nearby values: the replay keeps the pivots
    (no fall-back) and solves it as exactly as a fresh factorization."""
    A = _saddle(80, 25, 5)
    lu = LU(A)
    assert lu.factor(A) == 0
    rng = np.random.default_rng(7)
    B = A.copy()
    B.data *= 1.0 + 0.05 * rng.standard_normal(B.nnz)
    assert lu.refactor(B) == 0
    b = rng.standard_normal(A.shape[0])
    x = lu.solve(b)
    assert np.abs(B @ x - b).max() <= 1e-12 * abs(B).max() * np.abs(x).max()
    assert lu.counts() == [1, 1, 0]


def test_a_stale_pivot_sends_the_replay_back_to_a_full_factorization():
    """When a pivot of the old sequence becomes small next to its column the replay says so
    (1) and a full factorization chooses new pivots that solve the system."""
    A = sp.csc_matrix(np.array([[4.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 2.0]]))
    lu = LU(A)
    assert lu.factor(A) == 0
    B = A.copy()
    B.data[0] = 1e-9                      # the first pivot, 4, is now tiny next to the 1 below
    assert lu.refactor(B) == 1
    assert lu.factor(B) == 0
    b = np.array([1.0, 2.0, 3.0])
    np.testing.assert_allclose(lu.solve(b), np.linalg.solve(B.toarray(), b), rtol=1e-12)
    assert lu.counts() == [2, 1, 1]


def test_zero_entries_stay_out_of_the_pattern_until_they_are_nonzero():
    """Entries of the pattern whose value is zero (a planar mechanism's out-of-plane
    couplings) grow no fill: a full factorization leaves them out (fewer entries of L and U
    than with the same entries at 1e-300). A replay that meets one of them nonzero says so
    (1) and the factorization after it takes it in; from then on it is in the pattern, zero
    or not, until ps_lu_forget. Every solve is exact to rounding."""
    rng = np.random.default_rng(3)
    A = _saddle(80, 25, 9)
    off = np.flatnonzero((A.indices != np.repeat(np.arange(A.shape[1]), np.diff(A.indptr)))
                         & (A.data != 0.0))
    zeroed = rng.choice(off, len(off) // 2, replace=False)
    Z = A.copy()
    Z.data[zeroed] = 0.0
    tiny = Z.copy()
    tiny.data[zeroed] = 1e-300
    full, pruned = LU(A), LU(A)
    assert full.factor(tiny) == 0 and pruned.factor(Z) == 0
    assert lib.ps_lu_nnz(pruned.f) < 0.8 * lib.ps_lu_nnz(full.f)
    b = rng.standard_normal(A.shape[0])

    def exact(lu, M):
        x = lu.solve(b)
        assert np.abs(M @ x - b).max() <= 1e-12 * abs(M).max() * np.abs(x).max()

    exact(pruned, Z)
    small = lib.ps_lu_nnz(pruned.f)
    W = Z.copy()
    W.data[zeroed[0]] = 0.5                   # a left-out entry is nonzero now
    assert pruned.refactor(W) == 1
    assert pruned.factor(W) == 0
    exact(pruned, W)
    assert lib.ps_lu_nnz(pruned.f) >= small
    assert pruned.refactor(Z) == 0            # zero again: still in the pattern, replayed
    exact(pruned, Z)
    assert pruned.counts() == [2, 2, 1]
    lib.ps_lu_forget(pruned.f)
    assert pruned.refactor(Z) == -1 and pruned.factor(Z) == 0
    assert lib.ps_lu_nnz(pruned.f) == small


def test_fall_backs_leave_nothing_behind():
    """An entry that toggles between zero and nonzero costs one fall-back, the first time it
    is nonzero, and is replayed from then on. After ps_lu_forget nothing of the object's past
    (entries nonzero only in an earlier matrix, a replay that met a stale pivot, a singular
    factorization) shows: it factors and solves bit for bit as a fresh one does, so a restart
    does not depend on the runs before."""
    rng = np.random.default_rng(4)
    A = _saddle(60, 20, 4)
    rows = A.indices
    cols = np.repeat(np.arange(A.shape[1]), np.diff(A.indptr))
    off = np.flatnonzero((rows != cols) & (A.data != 0.0))
    A.data[rng.choice(off[1:], len(off) // 2, replace=False)] = 0.0     # zeros that matter
    toggle = off[0]
    Z = A.copy()
    Z.data[toggle] = 0.0
    lu = LU(A)
    assert lu.factor(Z) == 0
    for k in range(6):
        rc = lu.refactor(A if k % 2 == 0 else Z)
        assert rc == (1 if k == 0 else 0)
        if rc:
            assert lu.factor(A) == 0
    assert lu.counts() == [2, 6, 1]
    full = A.copy()
    full.data[full.data == 0.0] = 1.0                    # every entry in the pattern
    assert lu.factor(full) == 0
    stale = A.copy()
    stale.data[(rows == cols) & (rows < 60)] = 1e-9      # the mass diagonal's pivots collapse
    assert lu.refactor(stale) == 1
    dead = A.copy()
    dead.data[:] = 0.0
    assert lu.factor(dead) == 1                          # singular at its first step
    lib.ps_lu_forget(lu.f)
    fresh = LU(A)
    assert lu.factor(A) == 0 and fresh.factor(A) == 0
    b = rng.standard_normal(A.shape[0])
    assert np.array_equal(lu.solve(b), fresh.solve(b))
    assert lib.ps_lu_nnz(lu.f) == lib.ps_lu_nnz(fresh.f)


def test_singular_and_unfactored_matrices_are_reported():
    """A zero column is found at its step (k + 1); a replay before any factorization is -1;
    a non-finite value is no pivot."""
    A = sp.csc_matrix(np.array([[1.0, 0.0, 2.0], [0.0, 0.0, 1.0], [3.0, 0.0, 1.0]]))
    lu = LU(A)
    assert lu.refactor(A) == -1
    assert lu.factor(A) == 2
    C = sp.csc_matrix(np.array([[1.0, 2.0], [3.0, 4.0]]))
    lu = LU(C)
    bad = C.copy()
    bad.data[:] = [np.nan, np.nan, 1.0, 1.0]
    assert lu.factor(bad) == 1


def test_a_constrained_run_agrees_with_superlu_mt_and_the_dense_solver():
    """The slider-crank (exact joints, a motion, redundant equations removed) with its
    linear systems solved three ways from C: same answers to far below the tolerance."""
    model = pysolver.load(DECKS / "joints" / "slider_crank.xml")
    runs = {ls: model.run(linsolver=ls, integr_tol=1e-8)
            for ls in ("dense", "sparse", "superlu_mt")}
    for ls, res in runs.items():
        assert res.success, (ls, res.message)
        assert res.meta["options"]["backend"] == "c"
    ref = runs["dense"].request(1)
    for ls in ("sparse", "superlu_mt"):
        diff = runs[ls].request(1) - ref
        diff = np.remainder(diff + np.pi, 2 * np.pi) - np.pi    # an angle channel at +-pi
        assert np.nanmax(np.abs(diff)) < 1e-7
