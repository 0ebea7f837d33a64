"""Markers placed again from a case's numbers (a sweep's ``Reference_Marker/ID/pos_*``), as the
deck loader places them.

A marker's numbers are the deck's own: its ``pos_*`` in the frame of its ``rm_id`` (``RM``) when
it has one, an Adams QP in its part's frame, else global (:class:`pysolver.records.Placement`).
So a case is the deck edited by hand: the markers placed in a moved marker's frame move with it
(rm_id chains, across bodies too), a body's cg marker moves the body and its other markers stay
where the deck puts them, and the global places come out of the loader's own formula
(:func:`pysolver.deck.bodies.place`), bit for bit.
"""
from ..deck.bodies import place


class Places:
    """The places of a compiled model's markers (its working copy and its kernel).

    Parameters
    ----------
    model : pysolver.Model
        The compiled model's scene (its markers and bodies change).
    kernel : pysolver.build.kernel.Kernel
    """

    def __init__(self, model, kernel):
        self.model, self.kernel = model, kernel
        self.local = {}              # marker id -> its numbers (the deck's, or a case's)
        self.moved = set()           # markers whose numbers were set since the last sync
        self.movers = {}             # body id -> its markers (a cg marker moves them all)
        self.children = {}           # marker id -> the markers placed in its frame
        self.depth = {}              # marker id -> rm_id links to a marker placed without one
        for mid, pl in model.placements.items():
            if pl.rm is not None:
                self.children.setdefault(pl.rm, []).append(mid)

    def set(self, mid, axis, value):
        """One of marker mid's numbers (placed by :meth:`sync`)."""
        local = self.local.get(mid)
        if local is None:
            local = self.local[mid] = self.model.placements[mid].local.copy()
        local[axis] = value
        self.moved.add(mid)

    def forget(self):
        """Back to the deck's numbers (after a sync that put them back)."""
        self.local.clear()

    def sync(self):
        """Place the markers set since the last sync and those placed in their frames (an
        rm_id before the markers placed in its frame), in the model and in the kernel; returns
        the markers placed."""
        if not self.moved:
            return set()
        m = self.model
        todo, stack = set(), list(self.moved)
        while stack:
            mid = stack.pop()
            if mid not in todo:
                todo.add(mid)
                stack += self.children.get(mid, ())
        self.moved.clear()
        refresh = set()                       # markers whose place in the kernel changes
        for mid in sorted(todo, key=lambda x: (self._chain(x), x)):
            pl, mk = m.placements[mid], m.markers[mid]
            local = self.local.get(mid, pl.local)
            if pl.rm is not None:
                mk.pos[:] = place(m.markers[pl.rm].pos, pl.axes, local)
            elif pl.origin is not None:
                mk.pos[:] = place(pl.origin, pl.axes, local)
            else:
                mk.pos[:] = local
            body = m.bodies[mk.body]
            if body.kind != "ground" and body.cg == mid:
                body.pos[:] = mk.pos
                movers = self.movers.get(body.id)
                if movers is None:
                    movers = self.movers[body.id] = [x.id for x in m.markers.values()
                                                     if x.body == body.id]
                refresh.update(movers)
            else:
                refresh.add(mid)
        self._to_kernel(refresh)
        return todo

    def _to_kernel(self, markers):
        """The kernel's marker places (in their bodies' frames) of these markers."""
        m, k = self.model, self.kernel
        for mid in markers:
            x = m.markers[mid]
            body = m.bodies[x.body]
            row = k.marker_index.get(mid)
            if row is None or (body.kind != "ground" and body.cg == mid):
                continue                      # the cg marker stays at the body's origin
            local = x.pos if body.kind == "ground" else body.rot.T @ (x.pos - body.pos)
            k.arrays["marker_pos"][3 * row:3 * row + 3] = local

    def _chain(self, mid):
        got = self.depth.get(mid)
        if got is None:
            rm = self.model.placements[mid].rm
            got = self.depth[mid] = 0 if rm is None else self._chain(rm) + 1
        return got
