"""Force_Field and Force_Beam (Adams FIELD and BEAM), each held, as a Force_Bushing is
(pysolver/deck/vectors.py), as the vector force under its law key (pysolver.records.law_key):
six components in J's axes on I's body at I, their opposite on J's body at I's point (-F and
-T - d x F at J's origin, d = oI - oJ). docs/deck-language.md, "Fields and beams", gives the
sources and the decisions.

A field is the linear law of Adams' FIELD statement::

    F = -K (X - length) - C V + preload

X = (DX(I,J,J), DY(I,J,J), DZ(I,J,J), AX(I,J), AY(I,J), AZ(I,J)) the displacement of I
relative to J in J's axes (the rotations the single-axis angles Adams' FIESUB is given), V =
(VX(I,J,J,J), .., WX(I,J,J), ..) their rates as a bushing reads them, K and C full 6x6 (K[r][c]
multiplies X[c] in component r), C = cratio K when cratio is given.

A beam is the field of a massless uniform Timoshenko beam along J's x from J to I (length L
undeformed): its length is (L, 0, 0, 0, 0, 0) and its stiffness the closed form (E Young's
modulus, G the shear modulus, A the area, Ixx the torsion constant, Iyy and Izz the bending
moments about J's y and z, ASY and ASZ the shear area ratios)::

    K11 = E A / L                      K44 = G Ixx / L
    K22 = 12 E Izz / (L^3 (1 + Py))    K26 = K62 = -6 E Izz / (L^2 (1 + Py))
    K66 = (4 + Py) E Izz / (L (1 + Py))  Py = 12 E Izz ASY / (G A L^2)
    K33 = 12 E Iyy / (L^3 (1 + Pz))    K35 = K53 = +6 E Iyy / (L^2 (1 + Pz))
    K55 = (4 + Pz) E Iyy / (L (1 + Pz))  Pz = 12 E Iyy ASZ / (G A L^2)

The numbers the deck gives that are not zero are sweep parameters (``Force_Field/<id>/k26``,
``Force_Beam/<id>/e``, ...); a beam's stiffness entries are computed from its own on the
tape, so they follow a case's numbers.
"""
from ..records import Beam, Field
from .schema import SIX
from .vectors import DEFLECTIONS, RATES, check_bodies, check_markers, check_rigid, hold_law
from .vectors import measures as measure_pairs

_ROWS = range(6)
_USERSUB = ("usrsub_dll_name", "usrsub_fnc_name", "usrsub_param_string", "script_name",
            "interpreter")


# small algebra on (tree, text) pairs: None is zero ------------------------------------------
def _param(tag, eid, name, value):
    """A number of the element: a sweep parameter, or None when it is zero."""
    if not value:
        return None
    return ("param", f"{tag}/{eid}/{name}", float(value)), name


def _num(v):
    return ("num", v), repr(v)


def _bin(op, a, b, text):
    return ("bin", op, a[0], b[0]), text


def _times(a, b):
    """a b of two pairs (None when either is zero)."""
    if a is None or b is None:
        return None
    return _bin("*", a, b, f"{a[1]} {b[1]}")


def _law(stiffness, damping, cratio, length, preload, i, j):
    """Six (tree, text) components -K (X - length) - C V + preload; stiffness and damping 6x6
    of pairs or None, cratio a pair or None (C = cratio K), length and preload six."""
    xs, vs = measure_pairs(DEFLECTIONS, i, j), measure_pairs(RATES, i, j)
    deflection = []
    for x, v, off in zip(xs, vs, length):
        d = x if off is None else _bin("-", x, off, f"({x[1]} - {off[1]})")
        if cratio is not None:
            d = _bin("+", d, _times(cratio, v), f"({d[1]} + {cratio[1]} {v[1]})")
        deflection.append(d)
    out = []
    for r in _ROWS:
        terms = [_times(stiffness[r][c], deflection[c]) for c in _ROWS] + \
            [_times(damping[r][c], vs[c]) for c in _ROWS]
        total = None
        for term in terms:
            if term is None:
                continue
            total = (("neg", term[0]), f"-{term[1]}") if total is None else \
                _bin("-", total, term, f"{total[1]} - {term[1]}")
        if preload[r] is not None:
            total = preload[r] if total is None else \
                _bin("+", total, preload[r], f"{total[1]} + {preload[r][1]}")
        out.append(total if total is not None else (("num", 0.0), "0"))
    return [t for t, _ in out], [text for _, text in out]


def _matrix(a, prefix):
    """The 36 entries of matrix `prefix` (k or c) of attributes `a`, row by row."""
    return tuple(a[f"{prefix}{r + 1}{c + 1}"] for r in _ROWS for c in _ROWS)


def _damping(ctx, a, tag, eid):
    """(36 damping entries, cratio pair or None): cratio or c11..c66, not both."""
    damping = _matrix(a, "c")
    if a["cratio"] is not None and any(damping):
        first = next(f"c{r + 1}{c + 1}" for r in _ROWS for c in _ROWS if damping[6 * r + c])
        raise ctx.error(f"give cratio (C = cratio K) or the damping matrix ({first}...), not "
                        "both", "cratio")
    return damping, _param(tag, eid, "cratio", a["cratio"])


def _entries(tag, eid, prefix, values):
    return [[_param(tag, eid, f"{prefix}{r + 1}{c + 1}", values[6 * r + c]) for c in _ROWS]
            for r in _ROWS]


def _turns(rows):
    """Whether a 6x6 of pairs couples a rotation (a row or column past the third)."""
    return any(rows[r][c] is not None for r in _ROWS for c in _ROWS if r >= 3 or c >= 3)


def add_field(model, ctx, a):
    """Validate one Force_Field, add it and the vector force that holds its law."""
    ctx.id = fid = a["id"]
    tag = "Force_Field"
    given = next((k for k in _USERSUB if a.get(k) is not None), None)
    if given is not None:
        raise ctx.error("a nonlinear field (a FIESUB user subroutine) is not supported: give "
                        "its stiffness k11..k66 (and damping, length, preload)", given)
    check_markers(model, ctx, a, ("i_marker_id", "j_marker_id"))
    i, j = a["i_marker_id"], a["j_marker_id"]
    check_bodies(model, ctx, i, j, "a field")
    damping, cratio = _damping(ctx, a, tag, fid)
    field = Field(fid, i, j, _matrix(a, "k"), damping, a["cratio"],
                  tuple(a[f"length_{c}"] for c in SIX), tuple(a[f"preload_{c}"] for c in SIX),
                  a["label"])
    stiff, damp = _entries(tag, fid, "k", field.stiffness), _entries(tag, fid, "c", damping)
    length = [_param(tag, fid, f"length_{c}", v) for c, v in zip(SIX, field.length)]
    preload = [_param(tag, fid, f"preload_{c}", v) for c, v in zip(SIX, field.preload)]
    if _turns(stiff) or _turns(damp) or any(length[3:]) or any(preload[3:]):
        check_rigid(model, ctx, a, ("i_marker_id", "j_marker_id"), "a field's rotations")
    model.fields[fid] = field
    trees, texts = _law(stiff, damp, cratio, length, preload, i, j)
    hold_law(model, ctx, tag, fid, i, j, trees, texts, a["label"])


def beam_stiffness(p):
    """The 6x6 stiffness of a beam (the module's docstring) from its numbers `p` (name -> pair,
    None for a shear ratio of zero), as pairs (None: zero)."""
    e, g, area, length = p["e"], p["g"], p["area"], p["length"]
    k = [[None] * 6 for _ in _ROWS]
    k[0][0] = _bin("/", _times(e, area), length, "K11")
    k[3][3] = _bin("/", _times(g, p["ixx"]), length, "K44")
    l2 = _times(length, length)
    l3 = _times(l2, length)
    one = (("num", 1.0), "1")
    # bending in J's x-y plane (y and AZ, Izz, ASY), then in its x-z plane (z and AY, Iyy, ASZ)
    for t, r, inertia, ratio, sign in ((1, 5, p["izz"], p["asy"], -1.0),
                                       (2, 4, p["iyy"], p["asz"], 1.0)):
        ei = _times(e, inertia)
        n = str(t + 1) + str(r + 1)
        if ratio is None:
            phi, grow = None, one
        else:
            phi = _bin("/", _times(_times(_num(12.0), ei), ratio), _times(_times(g, area), l2),
                       "P")
            grow = _bin("+", one, phi, "1 + P")
        k[t][t] = _bin("/", _times(_num(12.0), ei), _times(l3, grow), f"K{t + 1}{t + 1}")
        k[t][r] = k[r][t] = _bin("/", _times(_num(6.0 * sign), ei), _times(l2, grow),
                                 f"K{n}")
        four = _num(4.0) if phi is None else _bin("+", _num(4.0), phi, "4 + P")
        k[r][r] = _bin("/", _times(four, ei), _times(length, grow), f"K{r + 1}{r + 1}")
    return k


def add_beam(model, ctx, a):
    """Validate one Force_Beam, add it and the vector force that holds its law."""
    ctx.id = bid = a["id"]
    tag = "Force_Beam"
    check_markers(model, ctx, a, ("i_marker_id", "j_marker_id"))
    i, j = a["i_marker_id"], a["j_marker_id"]
    check_bodies(model, ctx, i, j, "a beam")
    check_rigid(model, ctx, a, ("i_marker_id", "j_marker_id"), "a beam")
    damping, cratio = _damping(ctx, a, tag, bid)
    beam = Beam(bid, i, j, a["length"], a["e"], a["g"], a["area"], a["ixx"], a["iyy"],
                a["izz"], a["asy"], a["asz"], a["cratio"], damping,
                tuple(a[f"preload_{c}"] for c in SIX), a["label"])
    numbers = {k: _param(tag, bid, k, a[k]) for k in ("length", "e", "g", "area", "ixx",
                                                      "iyy", "izz", "asy", "asz")}
    length = [numbers["length"]] + [None] * 5
    preload = [_param(tag, bid, f"preload_{c}", v) for c, v in zip(SIX, beam.preload)]
    model.beams[bid] = beam
    trees, texts = _law(beam_stiffness(numbers), _entries(tag, bid, "c", damping), cratio,
                        length, preload, i, j)
    hold_law(model, ctx, tag, bid, i, j, trees, texts, a["label"])
