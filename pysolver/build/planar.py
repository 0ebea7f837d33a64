"""Planar scenes: rigid bodies that can only move in the global x-y plane, integrated in planar
coordinates.

A scene whose rigid bodies are held in a plane by revolute joints about the global z axis,
with gravity, initial velocities and every body's inertia giving no load out of that plane,
moves in the plane: its exact 3-D motion has z, the rotations about x and y, and the joints'
out-of-plane reactions constant (zero reactions). pysolver then integrates each body in
(x, y, rz) and (vx, vy, wz) (``PS_BODY_PLANAR``: 6 states instead of 13) and leaves out each
revolute's three out-of-plane equations (their reactions are zero), where the 3-D model
integrates all of them; the answers are the same motion (IFToMM A02: 970 unknowns instead of
2,023). Which scenes qualify is decided from the loaded numbers (:func:`planar_bodies`), strictly:
any element that could push a body out of its plane keeps the whole scene in 3-D. The
decision is documented in docs/numerics.md ("Planar scenes").
"""
import numpy as np

from .. import settings

#: Tables of element kinds a planar scene may have (records that act on no body, or only
#: read it, and joints, scalar forces and motions, each checked): anything else, a vector
#: force, a sensor, keeps the scene in 3-D.
ALLOWED = frozenset({"markers", "bodies", "joints", "sforces", "motions", "requests",
                     "graphics", "variables", "splines"})

#: Out-of-plane parts of derived numbers (unit axes, inertia products over the largest
#: principal moment, angular velocity over its size) below this count as zero.
TOL = 1e-12

#: A revolute's equations out of the plane (catalogue.JOINT_EQUATIONS["REVOLUTE"]: d along
#: global z, and its z axis's dot products with the other marker's x and y).
OUT_OF_PLANE = (2, 3, 4)


def scene_planar(model):
    """:func:`planar_bodies`, or none when ``PYSOLVER_PLANAR=off``."""
    return planar_bodies(model) if settings.planar() else frozenset()


def planar_bodies(model):
    """The ids of the moving bodies to integrate in planar coordinates: all of them when the
    scene is planar, else an empty frozenset (:func:`why_not`).

    A scene is planar when every moving body is a Body_Rigid; it has only the element kinds in
    :data:`ALLOWED`, every joint a REVOLUTE between markers whose z axes are the global z
    axis (either sense) at the same height, that of the centre of mass of each moving body
    they are on; every Force_Scalar_TwoBody a torque about a z axis along global z, or a
    force between two markers at that same kind of height (not action-only); every motion a
    rotation about z between markers whose z axes are along global z (a Motion_Joint on a
    revolute, or a Motion_Marker B3); only Transient Simulate commands; gravity without
    a z component; and each body starts with no z velocity, an angular velocity about global
    z only, and global z a principal axis of its inertia at its centre of mass.
    """
    if why_not(model) is not None:
        return frozenset()
    return frozenset(b.id for b in model.bodies.values() if b.kind != "ground")


def looks_planar(model):
    """Whether the scene's joints are all revolutes about global z (a user would call it a
    planar mechanism): when it is not planar, its log says why (:func:`why_not`)."""
    return bool(model.joints) and all(
        jo.type == "REVOLUTE" and _z_axis(model.markers[jo.i].rot)
        and _z_axis(model.markers[jo.j].rot) for jo in model.joints.values())


def why_not(model):
    """None for a planar scene (:func:`planar_bodies`), else the first reason it is not, as
    a phrase ("gravity has a z component")."""
    from .. import catalogue
    bodies = [b for b in model.bodies.values() if b.kind != "ground"]
    if not bodies:
        return "it has no moving body"
    for b in bodies:
        if b.kind != "rigid":
            return f"body {b.id} is a point body"
    for element in catalogue.ELEMENTS:
        if element.table not in ALLOWED and getattr(model, element.table):
            return f"it has {element.table} (not taken in a planar scene)"
    if any(cmd.analysis != "TRANSIENT" for cmd in model.commands):
        return "it has a Simulate command that is not Transient"
    if model.gravity[2] != 0.0:
        return "gravity has a z component"
    for b in bodies:
        why = _in_plane(b)
        if why:
            return f"body {b.id}'s {why}"
    for jo in model.joints.values():
        i, j = model.markers[jo.i], model.markers[jo.j]
        if jo.type != "REVOLUTE" or getattr(jo, "virtual", False):
            return f"Constraint_Joint {jo.id} is not a REVOLUTE"
        if not (_z_axis(i.rot) and _z_axis(j.rot)):
            return f"Constraint_Joint {jo.id}'s z axes are not along global z"
        if not all(_at_height(m, model.bodies[m.body], i.pos[2]) for m in (i, j)):
            return (f"Constraint_Joint {jo.id}'s markers are not at the height of the centres "
                    "of mass of their bodies")
    for sf in model.sforces.values():
        if not _in_plane_force(model, sf):
            return f"Force_Scalar_TwoBody {sf.id} acts out of the plane"
    # a driven rotation about z between frames turning about z: its reaction is a torque
    # about z (a tilted I frame would give AZ's gradient, and the torque, an x or y part)
    for mo in model.motions.values():
        if not (mo.direction == "B3" and _z_axis(model.markers[mo.i].rot)
                and _z_axis(model.markers[mo.j].rot)):
            return f"motion {mo.id} is not a rotation about global z"
    return None


def _in_plane_force(model, sf):
    """Whether a Force_Scalar_TwoBody acts in the plane only: a torque about J's z axis along
    global z, or a force along the line between I and J at the height of I and J and of
    the centres of mass of the moving bodies they are on (whatever its magnitude's
    expression). An action-only force acts along J's z axis: out of the plane."""
    i, j = model.markers[sf.i], model.markers[sf.j]
    if sf.action_only:
        return False
    if sf.torque:
        return _z_axis(j.rot)
    return all(_at_height(m, model.bodies[m.body], i.pos[2]) for m in (i, j))


def _at_height(marker, body, z):
    """Whether a joint marker is at height z and, on a moving body, at the height of its
    centre of mass: an in-plane joint force at another height has a moment about x or y on
    the body that the 3-D joint carries as an out-of-plane reaction (not zero)."""
    zs = [marker.pos[2]] + ([body.pos[2]] if body.kind != "ground" else [])
    scale = 1.0 + max(abs(v) for v in zs + [z])
    return all(abs(v - z) <= TOL * scale for v in zs)


def _z_axis(rot):
    """Whether a frame's z axis (third column) is the global z axis, either sense."""
    z = np.asarray(rot, dtype=float)[:, 2]
    return abs(z[0]) <= TOL and abs(z[1]) <= TOL


def _in_plane(b):
    """None when rigid body b starts moving in the x-y plane with no out-of-plane load of its
    own (its velocity, its angular velocity and the inertia about global z), else what is
    out of the plane."""
    if b.vel[2] != 0.0:
        return "initial velocity has a z component"
    w = b.rot @ np.asarray(b.omega, dtype=float)          # global angular velocity
    if abs(w[0]) > TOL * np.linalg.norm(w) or abs(w[1]) > TOL * np.linalg.norm(w):
        return "initial angular velocity is not about global z"
    Ig = global_inertia(b)
    big = max(np.abs(Ig).max(), np.finfo(float).tiny)
    if abs(Ig[0, 2]) > TOL * big or abs(Ig[1, 2]) > TOL * big:
        return "inertia has global xz or yz products (z is not a principal axis)"
    return None


def global_inertia(b):
    """Body b's inertia tensor about its centre of mass in global axes at t = 0."""
    return b.rot @ np.asarray(b.inertia, dtype=float) @ b.rot.T


def removed_rows(model, bodies):
    """The joint equations a planar scene leaves out: every revolute's out-of-plane ones."""
    if not bodies:
        return ()
    return tuple(("joint", jid, k) for jid in sorted(model.joints) for k in OUT_OF_PLANE)


def plane_rows(b):
    """Body b's ``body_plane`` entries: its axes at rz = 0 (row-major 3 x 3) and its z."""
    return list(np.asarray(b.rot, dtype=float).reshape(-1)) + [float(b.pos[2])]


def initial_state(b):
    """Body b's planar (x, y, rz) and (vx, vy, wz) at t = 0 (rz measured from its axes at
    t = 0)."""
    w = b.rot @ np.asarray(b.omega, dtype=float)
    return [b.pos[0], b.pos[1], 0.0], [b.vel[0], b.vel[1], w[2]]
