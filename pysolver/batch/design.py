"""Designs of a sweep: a full factorial grid and quasi-random samples (scipy.stats.qmc)."""
import itertools
import numbers

import numpy as np


def grid(values):
    """Every combination of the given values: ``grid({"A/1/x": [1, 2], "B/2/y": [3, 4]})`` is
    four cases, the last path varying fastest.

    Parameters
    ----------
    values : dict
        Path -> sequence of numbers.

    Returns
    -------
    list of dict
    """
    paths = list(values)
    # lists as given (a True among numbers stays True: the case's row says it is no number)
    lists = [list(v) if isinstance(v, (list, tuple)) else np.atleast_1d(v).tolist()
             for v in map(values.get, paths)]
    return [dict(zip(paths, combo)) for combo in itertools.product(*lists)]


def sample(ranges, n, method="sobol", seed=None):
    """n cases with each path drawn in its range by a low-discrepancy design.

    Parameters
    ----------
    ranges : dict
        Path -> (low, high).
    n : int
        Number of cases (Sobol designs are best at powers of 2).
    method : {"sobol", "lhs"}
        scipy.stats.qmc.Sobol (scrambled) or LatinHypercube.
    seed : int, optional
        For reproducible designs.

    Returns
    -------
    list of dict

    Raises
    ------
    ValueError
        `n` is not a whole number of at least 1, `method` is unknown, or a range is not
        (low, high) with low <= high.
    """
    from scipy.stats import qmc
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, numbers.Integral) or n < 1:
        raise ValueError(f"n must be an integer of at least 1 (the number of cases), got {n!r}")
    n = int(n)
    paths = list(ranges)
    if method == "sobol":
        engine = qmc.Sobol(d=len(paths), scramble=True, seed=seed)
    elif method == "lhs":
        engine = qmc.LatinHypercube(d=len(paths), seed=seed)
    else:
        raise ValueError(f"method must be 'sobol' or 'lhs', got {method!r}")
    lo = np.array([float(ranges[p][0]) for p in paths])
    hi = np.array([float(ranges[p][1]) for p in paths])
    if np.any(hi < lo):
        raise ValueError("each range must be (low, high) with low <= high")
    points = qmc.scale(engine.random(n), lo, hi) if np.any(hi > lo) else \
        np.tile(lo, (n, 1))
    return [dict(zip(paths, map(float, row))) for row in points]
