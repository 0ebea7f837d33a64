"""Post_Request's marker types as the eight expressions they stand for.

MARKER_DISPLACEMENT, MARKER_VELOCITY of marker I relative to J (default: the global frame),
components in ref_marker_id's axes (default: global); the channels are those Adams' REQUEST and
MotionSolve's msolve Request report (../shared/reference/elements.md section 6.2); angles in
radians, as every angle pysolver reports:

- MARKER_DISPLACEMENT: mag, x, y, z, -, psi, theta, phi (DM, DX/DY/DZ in RM, and the
  body-fixed 3-1-3 angles of I relative to J, which RM does not change);
- MARKER_VELOCITY: vm, vx, vy, vz, wm, wx, wy, wz (the velocity and angular velocity of I
  relative to J, time derivatives in the global frame, in RM's axes);
- MARKER_ACCELERATION: accm, accx, accy, accz, wdtm, wdtx, wdty, wdtz (the acceleration and
  angular acceleration of I relative to J, derivatives in the global frame, in RM's axes).
"""
from . import expr as ex

#: Marker request types pysolver does not compute yet, and why.
NOT_YET = {}

#: Channel names and functions of each marker request type (None: the unused channel).
CHANNELS = {
    "MARKER_DISPLACEMENT": (("mag", "DM", "ij"), ("x", "DX", "ijr"), ("y", "DY", "ijr"),
                            ("z", "DZ", "ijr"), None, ("psi", "PSI", "ij"),
                            ("theta", "THETA", "ij"), ("phi", "PHI", "ij")),
    "MARKER_VELOCITY": (("vm", "VM", "ij"), ("vx", "VX", "ijr"), ("vy", "VY", "ijr"),
                        ("vz", "VZ", "ijr"), ("wm", "WM", "ij"), ("wx", "WX", "ijr"),
                        ("wy", "WY", "ijr"), ("wz", "WZ", "ijr")),
    "MARKER_FORCE": (("fm", "FM", "ij"), ("fx", "FX", "ijr"), ("fy", "FY", "ijr"),
                     ("fz", "FZ", "ijr"), ("tm", "TM", "ij"), ("tx", "TX", "ijr"),
                     ("ty", "TY", "ijr"), ("tz", "TZ", "ijr")),
    "MARKER_ACCELERATION": (("accm", "ACCM", "ij"), ("accx", "ACCX", "ijr"),
                            ("accy", "ACCY", "ijr"), ("accz", "ACCZ", "ijr"),
                            ("wdtm", "WDTM", "ij"), ("wdtx", "WDTX", "ijr"),
                            ("wdty", "WDTY", "ijr"), ("wdtz", "WDTZ", "ijr")),
}


#: The force function of each elem_type of an ELEMENTAL_FORCE request (the type MotionView
#: writes for joint and bushing outputs), by the Adams statement's name or the XML element's.
ELEMENT_FUNCTIONS = {"JOINT": "JOINT", "JPRIM": "JOINT", "CONSTRAINT_JOINT": "JOINT",
                     "CONSTRAINT_JPRIM": "JOINT", "BUSHING": "BUSH", "FORCE_BUSHING": "BUSH",
                     "FIELD": "FIELD", "FORCE_FIELD": "FIELD", "BEAM": "BEAM",
                     "FORCE_BEAM": "BEAM",
                     "SPRINGDAMPER": "SPDP", "FORCE_SPRINGDAMPER": "SPDP", "SFORCE": "SFORCE",
                     "FORCE_SCALAR_TWOBODY": "SFORCE", "MOTION": "MOTION",
                     "MOTION_JOINT": "MOTION", "MOTION_MARKER": "MOTION"}
#: The channels of an ELEMENTAL_FORCE request: comp 1..8 of the element's force function.
FORCE_NAMES = ("fm", "fx", "fy", "fz", "tm", "tx", "ty", "tz")


def elemental_texts(a):
    """The eight expressions of an ELEMENTAL_FORCE request's attributes `a` (checked by
    :func:`elemental_channels`): ``FN(elem_id, jflag, 1..8, ref_marker_id)``."""
    fn = ELEMENT_FUNCTIONS[str(a["elem_type"]).upper()]
    ids = (a["elem_id"], int(a.get("jflag") or 0), a.get("ref_marker_id") or 0)
    return [f"{fn}({ids[0]},{ids[1]},{k},{ids[2]})" for k in range(1, 9)]


def elemental_channels(ctx, a, markers):
    """(trees, texts, names) of an ELEMENTAL_FORCE request: the force and torque of element
    elem_id of elem_type on I's body at I (jflag 0) or on J's at J (1), in ref_marker_id's
    axes (default: global); DeckError for what does not belong to one, or is missing. That
    the element exists is checked with the deck's other references."""
    if a["type"] != "ELEMENTAL_FORCE":
        key = "elem_type" if a.get("elem_type") is not None else \
            "elem_id" if a.get("elem_id") is not None else "jflag"
        raise ctx.error(f"{key} belongs to an ELEMENTAL_FORCE request, not {a['type']}", key)
    wrong = [k for k in ("i_marker_id", "j_marker_id", *(f"expr{n}" for n in range(1, 9)))
             if a.get(k) is not None]
    if wrong:
        raise ctx.error("an ELEMENTAL_FORCE request computes its channels from elem_type, "
                        "elem_id, jflag and ref_marker_id", wrong[0])
    if a.get("elem_type") is None:
        raise ctx.error("an ELEMENTAL_FORCE request needs elem_type", "elem_type")
    if str(a["elem_type"]).upper() not in ELEMENT_FUNCTIONS:
        raise ctx.error(f"got {a['elem_type']!r}; expected an element with a force function: "
                        "JOINT (JPRIM), BUSHING, FIELD, BEAM, SPRINGDAMPER, SFORCE or MOTION",
                        "elem_type")
    if a.get("elem_id") is None:
        raise ctx.error("an ELEMENTAL_FORCE request needs elem_id", "elem_id")
    if a.get("ref_marker_id") and a["ref_marker_id"] not in markers:
        raise ctx.error(f"marker {a['ref_marker_id']} does not exist", "ref_marker_id")
    texts = elemental_texts(a)
    trees = [ex.call(t[:t.index("(")], *[int(v) for v in t[t.index("(") + 1:-1].split(",")])
             for t in texts]
    names = [a.get(f"name{k + 1}") or FORCE_NAMES[k] for k in range(8)]
    return trees, texts, names


def marker_channels(ctx, a, markers):
    """(trees, texts, names) of the eight channels of a marker request; DeckError for a
    missing or unknown marker, a type not computed yet, or expressions given as well."""
    kind = a["type"]
    if kind in NOT_YET:
        raise ctx.error(f"type {kind} is not supported yet: {NOT_YET[kind]}", "type")
    given = [f"expr{k}" for k in range(1, 9) if a.get(f"expr{k}") is not None]
    if given:
        raise ctx.error(f"a {kind} request computes its channels; expressions belong to "
                        "type=\"EXPRESSION\"", given[0])
    if a.get("i_marker_id") is None:
        raise ctx.error(f"a {kind} request needs i_marker_id", "i_marker_id")
    role = {"i": a["i_marker_id"], "j": a.get("j_marker_id") or 0,
            "r": a.get("ref_marker_id") or 0}
    for key in ("i_marker_id", "j_marker_id", "ref_marker_id"):
        if a.get(key) and a[key] not in markers:
            raise ctx.error(f"marker {a[key]} does not exist", key)
    trees, texts, names = [], [], []
    for k, channel in enumerate(CHANNELS[kind]):
        if channel is None:
            trees.append(None)
            texts.append(None)
            names.append(a.get(f"name{k + 1}"))
            continue
        name, fn, roles = channel
        ids = [role[r] for r in roles]
        tree = ex.call(fn, *ids)
        text = f"{fn}({','.join(str(i) for i in ids)})"
        trees.append(tree)
        texts.append(text)
        names.append(a.get(f"name{k + 1}") or name)
    return trees, texts, names
