"""The column order in which csrc/sparselu.c factors a kernel's iteration matrix."""
import weakref

import numpy as np

_ORDERS = weakref.WeakKeyDictionary()


def column_order(kernel):
    """The sparse LU's fill-reducing column order of `kernel`'s iteration matrix (int32,
    computed once per kernel): step k factors column ``order[k]``.

    SuperLU's COLAMD ordering, through SciPy, of :meth:`Kernel.sparsity`, taken from a
    factorization with reproducible random values on the pattern (COLAMD reads only the
    pattern; its fill is within a few per cent of SuperLU's own on IFToMM A02); the natural
    order if that factorization fails (the LU then reports the singular matrix itself).
    """
    order = _ORDERS.get(kernel)
    if order is None:
        order = _ORDERS[kernel] = colamd(kernel.sparsity())
    return order


def colamd(pattern):
    """The COLAMD column order (int32) of a square CSC `pattern`, from a factorization with
    reproducible random values on it; the natural order if that fails (structurally
    singular: the LU then reports the singular matrix itself)."""
    import scipy.sparse.linalg as spl
    values = pattern.copy()
    values.data = np.random.default_rng(0).uniform(0.5, 1.5, values.nnz)
    try:
        order = np.argsort(spl.splu(values.tocsc(), permc_spec="COLAMD").perm_c)
    except RuntimeError:
        order = np.arange(pattern.shape[1])
    return np.ascontiguousarray(order, dtype=np.int32)
