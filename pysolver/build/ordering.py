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
        import scipy.sparse.linalg as spl
        pattern = kernel.sparsity().copy()
        pattern.data = np.random.default_rng(0).uniform(0.5, 1.5, pattern.nnz)
        try:
            order = np.argsort(spl.splu(pattern, permc_spec="COLAMD").perm_c)
        except RuntimeError:                      # structurally singular
            order = np.arange(kernel.ny)
        order = np.ascontiguousarray(order, dtype=np.int32)
        _ORDERS[kernel] = order
    return order
