"""The data of a Reference_Spline (or a SPLINE statement): x y pairs, checked at load; the
interpolation itself is pysolver.build.splines."""
import numpy as np

#: The fewest points each interpolation function takes.
FEWEST = {"LINSPL": 2, "CUBSPL": 4, "AKISPL": 4, "QUISPL": 6}


def parse_points(ctx, text, attribute):
    """x and y (tuples) from element text of x y pairs; DeckError on bad data."""
    try:
        vals = [float(v.replace("d", "e").replace("D", "e"))
                for v in text.replace(",", " ").split()]
    except ValueError:
        raise ctx.error("the spline's data are x y pairs of numbers", attribute) from None
    if len(vals) % 2:
        raise ctx.error(f"the spline's data are x y pairs; got {len(vals)} numbers",
                        attribute)
    return tuple(vals[0::2]), tuple(vals[1::2])


def check_points(ctx, x, y, attribute):
    """DeckError unless x is strictly increasing, finite, and there are at least 2 points."""
    if len(x) != len(y):
        raise ctx.error(f"x has {len(x)} values and y {len(y)}", attribute)
    if len(x) < 2:
        raise ctx.error(f"a spline needs at least 2 points; got {len(x)}", attribute)
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise ctx.error("the spline's data must be finite numbers", attribute)
    d = np.diff(x)
    if np.any(d <= 0):
        k = int(np.argmax(d <= 0))
        raise ctx.error(f"x must be strictly increasing; x[{k + 1}] = {x[k + 1]:g} follows "
                        f"x[{k}] = {x[k]:g}", attribute)
