"""Markers and bodies of a deck: global frames of markers, mass properties of bodies."""
import numpy as np

from ..model import Body, Marker, Placement, Rates
from ..rotations import along, rot_313, rot_321, rot_from_e

#: What a massless (dummy) part's deck must give instead (docs/deck-language.md).
MASSLESS = ("give it a small mass, a centre-of-mass marker and a small inertia "
            "(docs/deck-language.md, \"Massless parts\")")


def add_bodies(model, bodies_raw, markers_raw):
    """Resolve marker frames (through rm_id chains) and add the bodies and markers to model."""
    ground_ids = set()
    for ctx, a in bodies_raw:
        ctx.id = a["id"]
        if ctx.tag == "Body_Rigid" and a["isground"]:
            ground_ids.add(a["id"])
            model.bodies[a["id"]] = Body(a["id"], "ground", label=a["label"])
    # markers: global frames, resolving rm_id chains
    frames = {}

    def frame(mid, stack=()):
        if mid in frames:
            return frames[mid]
        ctx, a = markers_raw[mid]
        ctx.id = mid
        R = _orientation(ctx, a)
        p = np.array([a["pos_x"], a["pos_y"], a["pos_z"]])
        placed = Placement(p.copy())
        if a["rm_id"] is not None:
            if a["rm_id"] not in markers_raw:
                raise ctx.error(f"rm_id {a['rm_id']} is not a Reference_Marker", "rm_id")
            if a["rm_id"] in stack:
                raise ctx.error("rm_id chain refers back to this marker", "rm_id")
            p0, R0, _ = frame(a["rm_id"], stack + (mid,))
            placed = Placement(p.copy(), rm=a["rm_id"], axes=R0)
            p, R = place(p0, R0, p), R0 @ R
        # an Adams marker of a part whose frame is not the global one: the reader gives its
        # global place, and how QP placed it (pysolver.deck.adams, marker_reference)
        given = ctx.names.get("#placement")
        frames[mid] = (p, R, given if given is not None else placed)
        return frames[mid]

    for mid, (_, a) in markers_raw.items():
        p, R, placed = frame(mid)
        model.markers[mid] = Marker(mid, a["body_id"], p, R, a["label"], a["floating"])
        model.placements[mid] = placed

    # a marker on an undeclared body is its own error, before a body's cg_id names it
    declared = set(model.bodies) | {a["id"] for _, a in bodies_raw}
    for mid, (ctx, a) in markers_raw.items():
        ctx.id = mid
        if a["body_id"] not in declared:
            raise ctx.error(f"body {a['body_id']} does not exist (declare it with Body_Rigid, "
                            "Body_Point or a ground Body_Rigid isground=\"TRUE\")", "body_id")

    def marker_of(ctx, a, key):
        mid = a[key]
        if mid is None:
            return None
        if mid not in model.markers:
            raise ctx.error(f"marker {mid} does not exist", key)
        if model.markers[mid].body != a["id"]:
            raise ctx.error(f"marker {mid} belongs to body {model.markers[mid].body}, not to "
                            f"this body", key)
        return model.markers[mid]

    for ctx, a in bodies_raw:
        ctx.id = a["id"]
        if ctx.tag == "Body_Rigid" and a["isground"]:
            continue
        if a["cg_id"] is None:
            raise ctx.error("missing: the centre-of-mass marker, and pysolver has no massless "
                            f"parts: {MASSLESS}", "cg_id")
        if a["mass"] is None:
            raise ctx.error(f"missing: the mass, and pysolver has no massless parts: {MASSLESS}",
                            "mass")
        cg = marker_of(ctx, a, "cg_id")
        v_ic = np.array([a["v_ic_x"], a["v_ic_y"], a["v_ic_z"]])
        vm = _direction_marker(model, ctx, a, "vm_id")
        vel = velocity(v_ic, vm)
        w_ic = np.array([a.get("w_ic_x", 0.0), a.get("w_ic_y", 0.0), a.get("w_ic_z", 0.0)])
        wm = _direction_marker(model, ctx, a, "wm_id")
        # an Adams or msolve PART without WX..: those a sweep gives are along its CM marker
        wm_id = wm.id if wm is not None else ctx.names.get("#wm")
        model.rates[a["id"]] = Rates(v_ic, vm and vm.id, w_ic, wm_id)
        if ctx.tag == "Body_Point":
            model.bodies[a["id"]] = Body(a["id"], "point", a["mass"], None, cg.pos.copy(),
                                         np.eye(3), vel, np.zeros(3), a["label"], cg=cg.id)
            continue
        im = marker_of(ctx, a, "im_id") or cg
        lprf = marker_of(ctx, a, "lprf_id")
        if lprf is not None and not (np.allclose(lprf.pos, 0, atol=1e-12)
                                     and np.allclose(lprf.rot, np.eye(3), atol=1e-12)):
            ctx.warn(f"lprf_id {lprf.id} is not the global frame; marker positions and axes "
                     "are read as global, as MotionSolve's Reference_Marker defines them, so "
                     "the LPRF moves no marker (docs/deck-language.md, \"Placement\")",
                     "lprf_id")
        Iim = inertia_tensor(*(a[f"inertia_{k}"] for k in ("xx", "yy", "zz", "xy", "yz", "xz")))
        if not Iim.any():
            raise ctx.error("missing: the part has no inertia (all its moments are 0), and "
                            f"pysolver has no inertia-less parts: {MASSLESS}", "inertia_xx")
        if not positive_definite(Iim):
            raise ctx.error("the inertia tensor must be positive definite; its principal "
                            f"moments are {_moments(Iim)}", "inertia_xx")
        Rb = cg.rot.T @ im.rot      # im axes in the body (cg) frame
        d = cg.rot.T @ (im.pos - cg.pos)        # the im origin from the cg, body axes
        inertia = centroidal(Iim, Rb, a["mass"], d)
        if not positive_definite(inertia):
            raise ctx.error(f"the inertia about IM marker {im.id}'s origin, {_offset(d)} from "
                            "the centre of mass along the CM marker's axes, less the "
                            "parallel-axis term m(|d|^2 E - d d^T) is not positive definite: "
                            "give the inertia about the IM marker's origin, not about the "
                            "centre of mass", "im_id")
        bad = next((t for t in (Iim, inertia) if not triangle(t)), None)
        if bad is not None:
            ctx.warn(f"the principal moments of inertia {_moments(bad)} break the triangle "
                     "inequality (the largest is more than the sum of the other two; a rigid "
                     "body's never is); Adams takes such a part and so does pysolver: the "
                     "tensor is positive definite, so the motion is defined "
                     "(docs/deck-language.md, \"Mass properties\")", "inertia_xx")
        omega = spin(w_ic, cg, wm)
        model.bodies[a["id"]] = Body(a["id"], "rigid", a["mass"], inertia,
                                     cg.pos.copy(), cg.rot.copy(), vel, omega,
                                     a["label"], cg=cg.id, im_rot=Rb, inertia_im=Iim,
                                     im=im.id)


def inertia_tensor(xx, yy, zz, xy, yz, xz):
    """The inertia tensor of a deck's six numbers: the products are positive integrals,
    Ixy = +integral of x*y dm, as Adams' PART defines them, so the tensor holds -Ixy
    (docs/deck-language.md, "Products of inertia")."""
    return np.array([[xx, -xy, -xz], [-xy, yy, -yz], [-xz, -yz, zz]], dtype=float)


def centroidal(inertia_im, im_rot, mass, offset):
    """A body's inertia about its centre of mass in its own axes, from the tensor about the
    IM marker's origin along its axes (`im_rot`: the IM axes in the body's), the mass and
    the IM origin's `offset` from the centre of mass in body axes: turned into the body's
    axes, then moved to the centre of mass (parallel axes, I_cm = I_im - m(|d|^2 E - d d^T))."""
    inertia = im_rot @ inertia_im @ im_rot.T
    if not np.any(offset):
        return inertia
    d = np.asarray(offset, dtype=float)
    return inertia - mass * (d @ d * np.eye(3) - np.outer(d, d))


def positive_definite(inertia):
    """Whether a tensor can be a body's inertia in the equations of motion: positive
    definite (every principal moment > 0)."""
    return bool(np.linalg.eigvalsh(inertia).min() > 0)


def triangle(inertia):
    """Whether a positive definite tensor meets the triangle inequality (each principal moment
    at most the sum of the other two), as every rigid body's inertia does."""
    ev = np.linalg.eigvalsh(inertia)
    return bool(ev[2] <= ev[0] + ev[1] + 1e-12 * ev[2])


def _moments(inertia):
    return ", ".join(f"{v:.6g}" for v in np.linalg.eigvalsh(inertia))


def _offset(d):
    return "(" + ", ".join(f"{v:.6g}" for v in d) + ")"


def place(origin, axes, local):
    """A marker's global position from its deck numbers `local` in the frame (`origin`,
    `axes`) they are given in: the one formula the loaders and a sweep's marker paths use."""
    return origin + axes @ local


def velocity(v_ic, vm):
    """A body's initial velocity (global) from the deck's v_ic: along marker vm's axes when
    given (a Marker or None), else global."""
    return v_ic.copy() if vm is None else along(vm.rot, v_ic)


def spin(w_ic, cg, wm):
    """A rigid body's initial angular velocity in its own (cg marker's) axes: w_ic about the
    global axes, as MotionSolve's Body_Rigid defines it, or along wm_id's axes when given (the
    Adams and msolve readers give WX, WY, WZ with WM = the CM marker when no WM is given:
    Adams reads them along the CM marker's axes); docs/deck-language.md, "Initial angular
    velocity". `cg` and `wm` are Markers (wm may be None)."""
    if wm is not None and wm.id == cg.id:
        return w_ic.copy()
    return along(cg.rot.T if wm is None else cg.rot.T @ wm.rot, w_ic)


def _direction_marker(model, ctx, a, key):
    """The marker (on any body) whose axes give a body's initial velocity components."""
    mid = a.get(key)
    if mid is None:
        return None
    if mid not in model.markers:
        raise ctx.error(f"marker {mid} does not exist", key)
    return model.markers[mid]


def _orientation(ctx, a):
    """Marker axes (relative to its rm frame) from one of the orientation forms."""
    forms = {"matrix": ["a00", "a10", "a20", "a01", "a11", "a21", "a02", "a12", "a22"],
             "313": ["psi", "theta", "phi"], "321": ["yaw", "pitch", "roll"],
             "euler": ["e0", "e1", "e2", "e3"]}
    given = [f for f, keys in forms.items() if any(a[k] is not None for k in keys)]
    if len(given) > 1:
        raise ctx.error("give one orientation form only: a00..a22, psi/theta/phi, "
                        "yaw/pitch/roll or e0..e3", forms[given[1]][0])
    if not given:
        return np.eye(3)
    form = given[0]
    missing = [k for k in forms[form] if a[k] is None and form not in ("313", "321")]
    if missing:
        raise ctx.error(f"orientation form {', '.join(forms[form])} is incomplete", missing[0])
    if form in ("313", "321"):               # angles left out are 0
        return (rot_313 if form == "313" else rot_321)(*(a[k] or 0.0 for k in forms[form]))
    if form == "euler":
        e = np.array([a[k] for k in forms["euler"]])
        n = np.linalg.norm(e)
        if n == 0:
            raise ctx.error("Euler parameters are all zero", "e0")
        return rot_from_e(e / n)
    A = np.array([a[k] for k in forms["matrix"]]).reshape(3, 3).T
    if not np.allclose(A.T @ A, np.eye(3), atol=1e-6) or np.linalg.det(A) < 0:
        raise ctx.error("a00..a22 is not a proper rotation (orthonormal, right-handed)", "a00")
    u, _, vt = np.linalg.svd(A)
    return u @ vt

