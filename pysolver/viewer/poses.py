"""Where everything is at a run's output rows: each body's position and orientation, read
from the states a Result keeps (``res.y``: per point body q = (x, y, z), per rigid body
q = (x, y, z, e0..e3), per body of a planar scene q = (x, y, rz); columns named ``body<id>.x``
... by the kernel's layout), and each
marker's frame on its body, from the model's marker records as the kernel places it
(``pysolver/build/compiler.py``: s = A0^T (p0 - r0), axes A0^T M0)."""
import contextlib

import numpy as np

from ..rotations import e_from_rot


@contextlib.contextmanager
def scene_of(model, params=None):
    """The records a run drew on: `model` itself, or with `params` (a run's or a sweep case's
    numbers) its compiled scene with them applied, put back on exit."""
    if not params:
        yield model
        return
    parameters = model.compile().parameters
    parameters.apply(params)
    try:
        yield model.compile().model
    finally:
        parameters.reset()


def rotations(e):
    """Rotation matrices, shape (n, 3, 3), of Euler parameters e (n, 4), normalized first (the
    kernel's A = R(e) / |e|^2 is the same rotation)."""
    e = e / np.linalg.norm(e, axis=1)[:, None]
    e0, e1, e2, e3 = e.T
    return np.stack([
        np.stack([e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3),
                  2 * (e1 * e3 + e0 * e2)], axis=1),
        np.stack([2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3,
                  2 * (e2 * e3 - e0 * e1)], axis=1),
        np.stack([2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1),
                  e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3], axis=1)], axis=1)


def quaternion(R):
    """Unit quaternion (x, y, z, w), three.js's order, of one rotation matrix."""
    tr = np.trace(R)
    if tr > 0:
        w = 0.5 * np.sqrt(1 + tr)
        q = [(R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w),
             (R[1, 0] - R[0, 1]) / (4 * w), w]
    else:
        i = int(np.argmax(np.diag(R)))
        j, k = (i + 1) % 3, (i + 2) % 3
        v = 0.5 * np.sqrt(max(1 + R[i, i] - R[j, j] - R[k, k], 0.0))
        q = [0.0] * 4
        q[i] = v
        q[j] = (R[j, i] + R[i, j]) / (4 * v)
        q[k] = (R[k, i] + R[i, k]) / (4 * v)
        q[3] = (R[k, j] - R[j, k]) / (4 * v)
    q = np.array(q)
    return q / np.linalg.norm(q)


def planar_euler(rz, rot):
    """Unit Euler parameters of the axes Rz(rz) rot (rz an array of angles)."""
    e0 = e_from_rot(np.asarray(rot, dtype=float))       # rot's own, then a turn about z
    half = 0.5 * np.asarray(rz, dtype=float)
    c, s = np.cos(half), np.sin(half)
    # (c, 0, 0, s) * e0, the quaternion product
    return np.column_stack([c * e0[0] - s * e0[3], c * e0[1] - s * e0[2],
                            c * e0[2] + s * e0[1], c * e0[3] + s * e0[0]])


class Poses:
    """Body poses at output rows and marker frames on bodies.

    Parameters
    ----------
    model : pysolver.Model
        The records of the scene that ran (:func:`scene_of`).
    t, y : ndarray
        Output times (n,) and states (n, ny) of a Result.
    state_names : list of str
        The Result's names of the columns of `y`.

    Attributes
    ----------
    t : ndarray, shape (n,)
    ground : set of int
        Ids of the ground bodies.
    pos : dict
        Body id -> positions of its frame (its cg marker), shape (n, 3).
    euler : dict
        Rigid body id -> unit Euler parameters (e0, e1, e2, e3), shape (n, 4).
    local : dict
        Marker id -> (body id, position s in the body frame, axes in the body frame as
        columns); a ground marker's are global.
    """

    def __init__(self, model, t, y, state_names):
        self.t = np.asarray(t, dtype=float)
        y = np.asarray(y, dtype=float).reshape(len(self.t), -1)
        column = {name: k for k, name in enumerate(state_names)}
        self.ground, self.kind, self.pos, self.euler, self._rot = set(), {}, {}, {}, {}
        for bid, b in sorted(model.bodies.items()):
            self.kind[bid] = b.kind
            if b.kind == "ground":
                self.ground.add(bid)
                continue
            qa = column.get(f"body{bid}.x")
            if qa is None:
                raise ValueError(f"the Result has no states of body {bid}: it is not a run "
                                 f"of this model")
            if f"body{bid}.rz" in column:
                # a planar body (pysolver.build.planar): (x, y, rz), its z and its axes at
                # rz = 0 those it started with
                self.pos[bid] = np.column_stack([y[:, qa], y[:, qa + 1],
                                                 np.full(len(self.t), b.pos[2])])
                self.euler[bid] = planar_euler(y[:, qa + 2], b.rot)
                continue
            self.pos[bid] = y[:, qa:qa + 3]
            if b.kind == "rigid":
                e = y[:, qa + 3:qa + 7]
                self.euler[bid] = e / np.linalg.norm(e, axis=1)[:, None]
        self.local = {}
        for mid, m in sorted(model.markers.items()):
            b = model.bodies[m.body]
            if b.kind == "ground":
                self.local[mid] = (m.body, np.array(m.pos, float), np.array(m.rot, float))
            else:
                self.local[mid] = (m.body, b.rot.T @ (m.pos - b.pos), b.rot.T @ m.rot)

    def rotation(self, bid):
        """Orientation of body `bid` at each row, shape (n, 3, 3); None for a point body
        (never rotated) and the ground."""
        if bid not in self.euler:
            return None
        if bid not in self._rot:
            self._rot[bid] = rotations(self.euler[bid])
        return self._rot[bid]

    def marker_position(self, mid):
        """Global position of marker `mid` at each row, shape (n, 3)."""
        bid, s, _ = self.local[mid]
        if bid in self.ground:
            return np.tile(s, (len(self.t), 1))
        A = self.rotation(bid)
        return self.pos[bid] + (s if A is None else A @ s)

    def marker_axes(self, mid):
        """Global axes (columns x, y, z) of marker `mid` at each row, shape (n, 3, 3)."""
        bid, _, R = self.local[mid]
        A = self.rotation(bid)
        return np.tile(R, (len(self.t), 1, 1)) if A is None else A @ R
