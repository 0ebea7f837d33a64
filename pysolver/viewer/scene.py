"""The scene of an animation: poses at the output rows, what to draw for each element, the
scene's size (which scales the camera and every glyph) and the text on screen, gathered from
a Result and its model and written as the data the page's script reads."""
import base64
import numbers
import os

import numpy as np

from ..deck.dimensions import SYMBOLS
from ..deck.units import TIME as SECONDS
from . import shapes
from .poses import Poses, quaternion, scene_of

#: Body colours, in body id order (Tableau 10).
PALETTE = ("#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#76b7b2", "#edc948", "#b07aa1",
           "#ff9da7", "#9c755f", "#bab0ac")
#: Output rows an animation keeps at most by default (every k-th row beyond).
MAX_FRAMES = 4000


def rows_kept(n, max_frames):
    """Indices of the output rows an animation shows: all of them, or every k-th and the
    last when there are more than `max_frames`; TypeError when `max_frames` is not an int or
    None, ValueError when it is below 2."""
    if max_frames is not None and (isinstance(max_frames, bool) or
                                   not isinstance(max_frames, numbers.Integral)):
        raise TypeError(f"max_frames must be an int (at least 2) or None, got {max_frames!r} "
                        f"({type(max_frames).__name__})")
    if max_frames is not None and max_frames < 2:
        raise ValueError(f"max_frames must be at least 2 (the first and the last row), got "
                         f"{max_frames}")
    if max_frames is None or n <= max_frames:
        return np.arange(n)
    k = -(-(n - 1) // (max_frames - 1))
    rows = np.arange(0, n, k)
    return rows if rows[-1] == n - 1 else np.append(rows, n - 1)


def ordinal(k):
    """2 -> "2nd", 11 -> "11th", 23 -> "23rd"."""
    suffix = "th" if k % 100 in (11, 12, 13) else {1: "st", 2: "nd", 3: "rd"}.get(k % 10, "th")
    return f"{k}{suffix}"


def thinned(rows, total):
    """The note that says which output rows an animation keeps, or None when it keeps all."""
    if len(rows) == total:
        return None
    k = int(rows[1] - rows[0])
    last = " and the last" if (total - 1) % k else ""
    return f"showing {len(rows)} of {total} output rows (every {ordinal(k)}{last})"


def _finite(points):
    """The rows of `points` (k, 3) without NaN or infinity (a failed run's last rows)."""
    return points[np.all(np.isfinite(points), axis=1)]


def _b64(a, dtype):
    return base64.b64encode(np.ascontiguousarray(a, dtype=dtype).tobytes()).decode("ascii")


class Scene:
    """Everything an animation shows of one run.

    Parameters
    ----------
    result : pysolver.Result
    model : pysolver.Model
        The model that made it.
    params : dict, optional
        The run's numbers (``model.run(params=...)``, a sweep's case): marker positions
        they change are drawn where the run had them.
    max_frames : int or None
        Keep every output row up to this many, else every k-th row and the last.

    Attributes
    ----------
    poses : Poses
        Body poses at the rows shown (``poses.t``) and marker frames on their bodies.
    rows : ndarray
        The Result's rows shown.
    items : list of dict
        What is drawn besides the bodies, markers and ground (:mod:`.shapes`).
    notes : list of str
        Which output rows are shown when not all are (first), then elements not drawn, and
        why: the page's note list.
    radius : float
        Radius of the sphere around everything drawn, model length units.
    glyph : float
        The size of glyphs (joints, markers, body spheres): radius / 25.
    """

    def __init__(self, result, model, params=None, max_frames=MAX_FRAMES):
        n = len(result.t)
        if n == 0:
            raise ValueError("nothing to animate: the run has no output rows"
                             + (f" ({result.message})" if result.message else ""))
        self.rows = rows_kept(n, max_frames)
        self.total = n
        y = np.asarray(result.y).reshape(n, -1)[self.rows]
        with scene_of(model, params) as scene:
            self.poses = Poses(scene, np.asarray(result.t)[self.rows], y, result.state_names)
            self._gather(scene, result)

    # what is drawn --------------------------------------------------------------------------
    def _gather(self, scene, result):
        p = self.poses
        name = scene.source.file
        self.title = os.path.basename(name) if name and name != "<string>" else "deck text"
        self.length = SYMBOLS.get(scene.units["length"], scene.units["length"].lower())
        self.time = SYMBOLS.get(scene.units["time"], scene.units["time"].lower())
        self.seconds = SECONDS.get(scene.units["time"], 1.0)  # the playback speed
        grav = np.asarray(scene.gravity, float)
        self.up = -grav / np.linalg.norm(grav) if np.any(grav) else np.array([0, 0, 1.0])
        self.radius, self.origin = self._extent(scene)
        g = self.glyph = self.radius / 25
        self.items, drawn_on = [], set()
        note = thinned(self.rows, self.total)
        self.notes = [note] if note else []
        for gid, gr in sorted(scene.graphics.items()):
            if shapes._true(gr.attrs.get("hidden", "")):
                continue
            try:
                got = shapes.graphic(gr, scene.markers, p, g)
            except shapes.Skip as why:
                self.notes.append(f"Post_Graphic {gid} ({gr.type}): not drawn: {why}")
                continue
            self.items += got
            drawn_on.update(scene.markers[it["marker"]].body for it in got if "marker" in it)
        driven = {mo.joint for mo in scene.motions.values() if mo.joint}
        for jid, jo in sorted(scene.joints.items()):
            self.items += shapes.joint(jo, p, g, driven=jid in driven)
        for sd in scene.springdampers.values():
            self.items += shapes.spring(sd, g)
        for bu in scene.bushings.values():
            self.items += shapes.bushing(bu, g)
        for fi in scene.fields.values():
            self.items += shapes.field(fi, g)
        for be in scene.beams.values():
            self.items += shapes.beam(be, g)
        for sid, sf in sorted(scene.sforces.items()):
            if sid > 0 and not sf.torque and not sf.action_only:
                self.items += shapes.scalar_force(sf)
        self.items += shapes.penalty_planes(scene.penalties.values(), scene, p, g)
        self.bodies = []
        for k, bid in enumerate(sorted(p.pos)):
            b = scene.bodies[bid]
            self.bodies.append({"id": bid, "label": b.label, "kind": b.kind,
                                "color": PALETTE[k % len(PALETTE)],
                                "glyph": bid not in drawn_on})
        self.status = {"success": bool(result.success), "message": str(result.message)}
        self.events = [{"t": float(e.time), "label": f"Sensor_Event {e.sensor}"
                        + (f" {e.label}" if e.label else "")} for e in result.events]

    def _extent(self, scene):
        """Radius and centre of the sphere around every marker at every row shown (ground
        markers that no joint or force uses left out, unless nothing moves)."""
        p = self.poses
        moving = [mid for mid, (bid, _, _) in p.local.items() if bid not in p.ground]
        pts = [p.marker_position(mid) for mid in moving] + [p.pos[b] for b in p.pos]
        used = set()
        for jo in scene.joints.values():
            used.update((jo.i, jo.j))
        for el in [*scene.springdampers.values(), *scene.bushings.values(),
                   *scene.fields.values(), *scene.beams.values(), *scene.sforces.values()]:
            used.update((el.i, el.j))
        pts += [p.marker_position(mid)[:1] for mid in sorted(used) if mid in p.local]
        pts = _finite(np.concatenate(pts)) if pts else np.zeros((0, 3))
        if not len(pts):                # no finite position at all (a run that diverged)
            pts = np.zeros((1, 3))
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        radius = float(np.linalg.norm(hi - lo)) / 2
        if radius == 0:     # nothing moves and one point: one unit of the deck's lengths
            radius = 1.0
        centre = (lo + hi) / 2
        # the floor: under the lowest point along up
        self.floor = float(((pts - centre) @ self.up).min()) - 0.08 * radius
        return radius, centre

    def view(self):
        """Direction from the scene's centre to the camera: across the plane the motion
        spans most (its least-varying direction), raised a little toward up."""
        p, up = self.poses, self.up
        step = max(1, len(p.t) // 200)
        pts = [p.marker_position(mid)[::step] for mid, (bid, _, _) in p.local.items()
               if bid not in p.ground]
        normal = None
        if pts:
            pts = _finite(np.concatenate(pts))
            if len(pts) >= 3 and np.ptp(pts, axis=0).max() > 1e-9 * self.radius:
                w, vecs = np.linalg.eigh(np.cov((pts - pts.mean(axis=0)).T))
                normal = vecs[:, 0]
        if normal is None or abs(normal @ up) > 0.8:
            # no plane of motion, or a horizontal one: look from a corner
            side = np.cross(up, [1.0, 0, 0] if abs(up[0]) < 0.9 else [0, 1.0, 0])
            normal = -np.cross(side, up) + 0.6 * side
        normal = normal - (normal @ up) * up
        normal /= np.linalg.norm(normal)
        right = np.cross(-normal, up)
        if right.sum() < 0:
            normal = -normal
        d = normal + 0.3 * up + 0.15 * np.cross(-normal, up)
        return d / np.linalg.norm(d)

    # the page's data ------------------------------------------------------------------------
    def data(self):
        """The scene as the page's script reads it (JSON-ready; poses as base64 float32
        relative to ``origin``, times as base64 float64)."""
        p, o = self.poses, self.origin
        bodies = []
        for b in self.bodies:
            e = p.euler.get(b["id"])
            quat = None if e is None else _b64(np.column_stack([e[:, 1:], e[:, :1]]),
                                               np.float32)
            bodies.append(dict(b, pos=_b64(p.pos[b["id"]] - o, np.float32), quat=quat))
        markers = []
        for mid, (bid, s, R) in p.local.items():
            ground = bid in p.ground
            markers.append({"id": mid, "body": 0 if ground else bid,
                            "p": (s - o if ground else s).tolist(),
                            "q": quaternion(R).tolist()})
        items = []
        for it in self.items:
            if it["kind"] == "plane":
                it = dict(it, centre=(np.asarray(it["centre"]) - o).tolist())
            items.append(it)
        return {"title": self.title, "length": self.length, "time": self.time,
                "seconds": self.seconds,
                "n": len(p.t), "total": self.total, "t": _b64(p.t, np.float64),
                "origin": o.tolist(), "radius": self.radius, "glyph": self.glyph,
                "up": self.up.tolist(), "floor": self.floor, "view": self.view().tolist(),
                "bodies": bodies, "markers": markers, "items": items, "notes": self.notes,
                "status": self.status, "events": self.events}
