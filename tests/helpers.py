"""Paths and numerical helpers shared by the tests (the fixtures are in conftest.py)."""
import pathlib

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
DECKS = ROOT / "decks"
TEST_DECKS = pathlib.Path(__file__).resolve().parent / "decks"


def fd_iteration_matrix(kernel, t, y, yp, cj, rel=1e-5):
    """Central finite-difference dF/dy + cj dF/dyp of the kernel residual."""
    n = kernel.ny
    J = np.zeros((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = h = rel * max(1.0, abs(y[j]))
        J[:, j] = (kernel.residual_array(t, y + e, yp) - kernel.residual_array(t, y - e, yp)) / (2 * h)
        e[j] = h = rel * max(1.0, abs(yp[j]))
        J[:, j] += cj * (kernel.residual_array(t, y, yp + e) - kernel.residual_array(t, y, yp - e)) / (2 * h)
    return J

