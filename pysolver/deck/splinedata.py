"""The data of a Reference_Spline (or a SPLINE statement): x y pairs, or a surface's table,
checked at load; the interpolation itself is pysolver.build.splines."""
import numpy as np

from ..records import Spline

#: The fewest points each interpolation function takes.
FEWEST = {"LINSPL": 2, "CUBSPL": 4, "AKISPL": 4, "QUISPL": 6}


def _numbers(ctx, text, attribute, what):
    try:
        return [float(v.replace("d", "e").replace("D", "e"))
                for v in text.replace(",", " ").split()]
    except ValueError:
        raise ctx.error(f"the spline's data are {what} of numbers", attribute) from None


def parse_points(ctx, text, attribute):
    """x and y (tuples) from element text of x y pairs; DeckError on bad data."""
    vals = _numbers(ctx, text, attribute, "x y pairs")
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
    _increasing(ctx, x, "x", attribute)


def _increasing(ctx, v, name, attribute):
    """DeckError naming the first value of v that does not follow its predecessor upwards."""
    d = np.diff(v)
    if np.any(d <= 0):
        k = int(np.argmax(d <= 0))
        raise ctx.error(f"{name} must be strictly increasing; {name}[{k + 1}] = {v[k + 1]:g} "
                        f"follows {name}[{k}] = {v[k]:g}", attribute)


def parse_table(ctx, text, nz, attribute):
    """x, y and z (tuples) of a surface from element text laid out as MotionView's 3-D
    spline table: the nz z values, then one row per x value, x followed by y at each z.
    y comes back curve after curve (the nz curves, each len(x) long)."""
    vals = _numbers(ctx, text, attribute, "a table")
    if len(vals) < nz or (len(vals) - nz) % (nz + 1):
        raise ctx.error(f"a surface's text is its {nz} z values, then rows of an x value and "
                        f"{nz} y values; got {len(vals)} numbers", attribute)
    z = tuple(vals[:nz])
    rows = np.asarray(vals[nz:], float).reshape(-1, nz + 1)
    return tuple(rows[:, 0].tolist()), tuple(rows[:, 1:].T.ravel().tolist()), z


def check_surface(ctx, z, attribute):
    """DeckError unless the z values are finite and strictly increasing."""
    if len(z) < 1 or not np.all(np.isfinite(z)):
        raise ctx.error("a surface needs at least one finite z value", attribute)
    _increasing(ctx, z, "z", attribute)


def add_spline(model, ctx, a):
    """A Reference_Spline: x y pairs as its text (or X, Y from the SPLINE statement), or with
    num_z a surface's table (pysolver.deck.splinedata.parse_table)."""
    ctx.id = a["id"]
    if a.get("#text") is None:
        raise ctx.error("a Reference_Spline holds its x y pairs as the element's text", "#text")
    nz = a["num_z"]
    if nz is None:
        x, y = parse_points(ctx, a["#text"], "#text")
        z = ()
    else:
        x, y, z = parse_table(ctx, a["#text"], nz, "#text")
        check_surface(ctx, z, "#text")
    if a["num_xy_pair"] is not None and a["num_xy_pair"] != len(x):
        raise ctx.error(f"num_xy_pair is {a['num_xy_pair']} but the text has {len(x)} "
                        f"{'rows' if z else 'pairs'}", "num_xy_pair")
    spline = Spline(a["id"], x, y, bool(a["linear_extrap"] or a["linear_extrapolate"]),
                    a["label"], z)
    for k in range(max(len(z), 1)):
        check_points(ctx, x, spline.curve(k).y if z else y, "#text")
    model.splines[a["id"]] = spline
    model._where[("spline", a["id"])] = ctx
