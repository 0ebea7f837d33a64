"""The C form of :func:`~.consistent.consistent` away from the initial state
(``ps_restart_consistent`` and ``ps_motion_reactions``, csrc/control.c): the state indices and
the workspace of a kernel's restarts, allocated once per kernel. LoadControl restarts through
it on both paths of a run, so the two agree to the bit.

Dense scenes work on full iteration matrices. From SPARSE_THRESHOLD states the matrices are the
values of the kernel's CSC pattern (:meth:`Kernel.sparsity`) and the saddle-point system of
the accelerations is factored by the sparse LU (csrc/sparselu.c) on a pattern, its value
sources and a fill-reducing column order built here once; the least-change steps keep a dense
matrix of the held rows (nlam x nlam), so scenes with more than :data:`SPARSE_LIMIT` entries
in it or in the motions' least squares (nlam x the force rows) restart in Python.
"""
import numpy as np

from .. import catalogue
from ..deck import expr as ex
from ..options import SPARSE_THRESHOLD
from .consistent import _velocities
from .ordering import colamd

#: Most doubles of the sparse restart's dense work (nlam x max(nlam, force rows)): 32 MB.
SPARSE_LIMIT = 4_000_000


class Restart:
    """A kernel's ``psRestart``: see the module docstring. ``r`` is the struct."""

    def __init__(self, kernel):
        from .bindings import ffi
        lay, ny = kernel.layout, kernel.ny
        self.sparse = ny >= SPARSE_THRESHOLD
        ints = {"lam": lay.lam, "mu": lay.mu, "rate": lay.rate,
                "disp": np.nonzero(np.array(lay.mu, dtype=int) >= 0)[0],
                "turns": list(lay.turns.values()), "uidx": _velocities(lay),
                "row": np.setdiff1d(np.arange(ny), lay.algebraic)}
        nl, nr = len(lay.lam), len(ints["row"])
        jn = ny * ny
        if self.sparse:
            pattern = kernel.sparsity()
            jn = pattern.nnz
        sizes = {"J0": jn, "J1": jn, "res": ny, "res2": ny, "dx": ny, "g": nl, "z": nl,
                 "z2": nl, "lamv": nl, "cc": nl * nl,
                 "saddle": 1 if self.sparse else (nr + nl) ** 2, "rhs": nr + nl,
                 "ybak": ny, "ypbak": ny, "y0": ny, "wt": ny, "chg": ny,
                 "pull": 2 * ny}
        self.r = r = ffi.new("psRestart *")
        self.keep = []
        for name, values in ints.items():
            setattr(r, name, self._ints(values))
        for name, size in sizes.items():
            setattr(r, name, self._doubles(size))
        r.rows = self._ints(np.zeros(nl))
        r.nlam, r.ndisp, r.nturn = nl, len(ints["disp"]), len(ints["turns"])
        r.nu, r.nrow = len(ints["uidx"]), nr
        if self.sparse:
            self._sparse(kernel, pattern, ints)

    def _ints(self, values):
        from .bindings import ffi
        arr = np.ascontiguousarray(list(values) or [0], dtype=np.int32)
        self.keep.append(arr)
        return ffi.cast("int *", ffi.from_buffer(arr))

    def _doubles(self, values):
        from .bindings import ffi
        arr = np.zeros(max(values, 1)) if np.isscalar(values) else \
            np.ascontiguousarray(values, dtype=float)
        self.keep.append(arr)
        return ffi.cast("double *", ffi.from_buffer(arr))

    def _sparse(self, kernel, pattern, ints):
        """The sparse fields: the pattern, each reaction's row in it, and the saddle-point
        matrix [D[row, row] J0[row, lam]; J0[lam, row] 0] (D = J1 - J0) on its own pattern
        with the source of each entry, factored in a COLAMD column order."""
        import scipy.sparse as sp

        from .bindings import ffi, lib
        r, ny = self.r, kernel.ny
        lam, row = np.asarray(ints["lam"], dtype=int), np.asarray(ints["row"], dtype=int)
        nl, nr = len(lam), len(row)
        r.sparse, r.jnnz = 1, pattern.nnz
        tmap = kernel.csc_map()
        r.jmap, r.ntrip = self._ints(tmap), len(tmap)
        r.jcolptr, r.jrowind = self._ints(pattern.indptr), self._ints(pattern.indices)
        # the entries of the pattern by row: value index and column
        at = pattern.copy()
        at.data = np.arange(pattern.nnz, dtype=float)
        csr = at.tocsr()
        ptr, vals, cols = [0], [], []
        for i in lam:
            a, b = csr.indptr[i], csr.indptr[i + 1]
            vals.extend(csr.data[a:b].astype(int))
            cols.extend(csr.indices[a:b])
            ptr.append(len(vals))
        r.lrow_ptr, r.lrow_at, r.lrow_col = self._ints(ptr), self._ints(vals), self._ints(cols)
        is_u = np.zeros(ny, dtype=np.int32)
        is_u[np.asarray(ints["uidx"], dtype=int)] = 1
        rowpos = np.full(ny, -1, dtype=np.int32)
        rowpos[row] = np.arange(nr)
        lampos = np.full(ny, -1, dtype=np.int32)
        lampos[lam] = np.arange(nl)
        r.is_u, r.rowpos, r.w = self._ints(is_u), self._ints(rowpos), self._doubles(ny)
        r.qr = self._doubles(nr * nl)
        # the saddle-point matrix's entries from the pattern's (row i, column j, value e)
        coo = at.tocoo()
        i, j, e = coo.row, coo.col, coo.data.astype(int)
        blocks = []
        keep = (rowpos[i] >= 0) & (rowpos[j] >= 0)                   # D = J1 - J0
        blocks.append((rowpos[i[keep]], rowpos[j[keep]], e[keep], e[keep], -1.0))
        keep = (rowpos[i] >= 0) & (lampos[j] >= 0)                   # J0[row, lam]
        blocks.append((rowpos[i[keep]], nr + lampos[j[keep]], -1, e[keep], 1.0))
        keep = (lampos[i] >= 0) & (rowpos[j] >= 0)                   # J0[lam, row]
        blocks.append((nr + lampos[i[keep]], rowpos[j[keep]], -1, e[keep], 1.0))
        si = np.concatenate([b[0] for b in blocks])
        sj = np.concatenate([b[1] for b in blocks])
        one = np.concatenate([np.broadcast_to(b[2], len(b[0])) for b in blocks])
        zero = np.concatenate([b[3] for b in blocks])
        sign = np.concatenate([np.full(len(b[0]), b[4]) for b in blocks])
        order = np.lexsort((si, sj))                                 # CSC: by column, row
        si, sj, one, zero, sign = si[order], sj[order], one[order], zero[order], sign[order]
        n = nr + nl
        colptr = np.searchsorted(sj, np.arange(n + 1)).astype(np.int32)
        r.snnz = len(si)
        r.s_one, r.s_zero, r.s_sign = self._ints(one), self._ints(zero), self._doubles(sign)
        r.sval = self._doubles(len(si))
        colptr_c, rowind_c = self._ints(colptr), self._ints(si)
        corder = self._ints(colamd(sp.csc_matrix((np.ones(len(si)), si, colptr), shape=(n, n))))
        lu = lib.ps_lu_new(n, colptr_c, rowind_c, corder)
        if lu == ffi.NULL:
            raise MemoryError("could not allocate the sparse restart's LU")
        self.lu = ffi.gc(lu, lib.ps_lu_free)
        r.slu = self.lu

    @classmethod
    def of(cls, kernel):
        """The kernel's Restart (built once), or None for a sparse scene whose dense work
        would pass SPARSE_LIMIT (:func:`~.consistent.consistent` works there, in Python)."""
        if getattr(kernel, "_restart", None) is None:
            lay = kernel.layout
            nl, nr = len(lay.lam), kernel.ny - len(lay.algebraic)
            if kernel.ny >= SPARSE_THRESHOLD and nl * max(nl, nr) > SPARSE_LIMIT:
                return None
            kernel._restart = cls(kernel)
        return kernel._restart


def exact_rows(model, kernel, on=True):
    """Have the kernel's output rows take exact accelerations and reactions (``ps_row_exact``,
    through its :class:`Restart`) in a scene with reactions (`on`), or IDA's (not `on`); the
    flags once per kernel. A sparse scene past SPARSE_LIMIT keeps IDA's. The rows' rate
    equations read time with motions or general constraints; their force rows are linear in
    the accelerations and reactions unless an element's expression reads either (or a
    routine the kernel calls may)."""
    from ..deck.references import _expressions
    from .bindings import ffi
    restart = Restart.of(kernel) if kernel.layout.lam and on else None
    if restart is None:
        kernel.d.rows = ffi.NULL
        return
    if kernel.d.rows == restart.r:
        return
    late = {"accelerations", "forces"}
    reads = {n[1] for key, _, tree in _expressions(model)
             if key[0] not in ("request", "sensor", "evaluate") for n in ex.nodes(tree)
             if n[0] == "call" and n[1] in catalogue.FUNCTIONS}
    restart.r.row_timed = int(bool(model.motions or model.gcons))
    restart.r.row_linear = int(not kernel.model_calls_routines and not any(
        catalogue.FUNCTIONS[f].reads & late for f in reads))
    kernel.d.rows = restart.r
