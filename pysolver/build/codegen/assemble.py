"""The residual F(t, y, yp), the iteration matrix dF/dy + cj dF/dyp, the sensor expressions
and the request channels of a :class:`~.scene.Scene`, as graph nodes (csrc/residual.c)."""
from ... import catalogue
from ..bindings import lib

#: The element table's kinds by their PS_EL_* value.
KINDS = {getattr(lib, e.c): e for e in catalogue.TABLE_KINDS}


class Assembly:
    """Symbolic residual rows, Jacobian triplets, sensor values and outputs.

    Parameters
    ----------
    scene : Scene
    bodies, elements : bool, optional
        Whether the rows take the bodies' kinematic and inertia terms, and the elements' forces
        and motion constraints (:mod:`~.looped` assembles them one body or element at a time).

    Attributes
    ----------
    res : list of int
        Residual row nodes (the contributions to them, for part of a scene).
    trip : list of (row, col, node)
        Structural nonzeros of the iteration matrix, column-major and sorted.
    sensors, outputs : list of int or None
        Sensor expression nodes; request channel nodes (None: a NULL channel).
    """

    def __init__(self, scene, bodies=True, elements=True):
        self.s = scene
        g, a = scene.g, scene.a
        self.res = [g.zero] * scene.ny
        if bodies:
            self._inertia()
        if elements:
            for e in range(int(a["nel"])):
                kind = KINDS[int(a["el_kind"][e])]
                adr = int(a["el_adr"][e])
                ints = [int(v) for v in a["el_int"][adr:adr + len(kind.ints)]]
                # one contribution per kind, as csrc/elements/<kind>.c
                getattr(self, "_" + kind.kind)(int(a["el_tape"][e]), *ints)
        self.trip = self._jacobian()
        self.sensors = [scene.tape(int(t))[int(s)]
                        for t, s in zip(a["sensor_tape"][:a["nsensor"]],
                                        a["sensor_slot"][:a["nsensor"]])]
        self.outputs = [None if t < 0 else scene.tape(int(t))[int(s)]
                        for t, s in zip(a["out_tape"][:a["nout"]], a["out_slot"][:a["nout"]])]

    # rows -------------------------------------------------------------------------------
    def scatter(self, row, Q):
        """Subtract force_scale * Q from residual row `row`."""
        g = self.s.g
        self.res[row] = g.sub(self.res[row], g.mul(g.const(self.s.cf), Q))

    def _inertia(self):
        s, g, a = self.s, self.s.g, self.s.a
        y, yp = s.y, s.yp
        for b in range(int(a["nbody"])):
            kb = s.body(b)
            qa, ua = kb["qa"], kb["ua"]
            mass = s.par("body_mass", b)
            for i in range(3):
                self.res[qa + i] = g.sub(yp[qa + i], y[ua + i])
                if kb["planar"] and i == 2:       # Izz wz', no gravity about z
                    self.res[ua + i] = g.mul(s.par("body_inertia", b, 8), yp[ua + i])
                    continue
                self.res[ua + i] = g.mul(mass, g.sub(yp[ua + i], s.par("gravity", 0, i)))
            if not kb["rigid"]:
                continue
            e, w = kb["e"], kb["wb"]
            G = [[g.neg(e[1]), g.neg(e[2]), g.neg(e[3])], [e[0], g.neg(e[3]), e[2]],
                 [e[3], e[0], g.neg(e[1])], [g.neg(e[2]), e[1], e[0]]]
            for r in range(4):
                row = yp[qa + 3 + r]
                for k in range(3):
                    row = g.sub(row, g.mul(g.mul(g.const(0.5), G[r][k]), w[k]))
                self.res[qa + 3 + r] = row
            Im = [s.par("body_inertia", b, k) for k in range(9)]
            wd = yp[ua + 3:ua + 6]
            Iw, Iwd = s.mat_vec(Im, w), s.mat_vec(Im, wd)
            for i in range(3):
                j, k = (i + 1) % 3, (i + 2) % 3
                self.res[ua + 3 + i] = g.sub(g.add(Iwd[i], g.mul(w[j], Iw[k])), g.mul(w[k], Iw[j]))

    def rate_force(self, tape, gnode, F):
        """Q_i = F d(g')/du_i on every body the tape reads."""
        s, g = self.s, self.s.g
        for b in s.tape_bodies(tape):
            ua = s.body(b)["ua"]
            for i in range(s.nu(b)):
                self.scatter(ua + i, g.mul(F, s.rate_coeff(gnode, b, i)))

    def _penalty(self, tape, g, f):
        slots = self.s.tape(tape)
        self.rate_force(tape, slots[g], slots[f])

    def apply_at(self, tape, slot, P, F, Mo, sign):
        """Generalized forces of a global force F at the global point P and a moment Mo."""
        s, g = self.s, self.s.g
        if slot < 0:
            return
        kb = s.body(s.slot_body(tape, slot))
        ua = kb["ua"]
        if kb["planar"]:                  # (Fx, Fy, Mz about the origin): csrc/assembly.c
            Q = g.zero
            if F is not None:
                for i in range(2):
                    self.scatter(ua + i, g.lin(sign, F[i]))
                p = g.vsub(P, kb["r"])
                Q = g.sub(g.mul(p[0], F[1]), g.mul(p[1], F[0]))
            if Mo is not None:
                Q = g.add(Q, Mo[2])
            self.scatter(ua + 2, g.lin(sign, Q))
            return
        if F is not None:
            for i in range(3):
                self.scatter(ua + i, g.lin(sign, F[i]))
        if not kb["rigid"]:
            return
        mom = g.cross(g.vsub(P, kb["r"]), F) if F is not None else [g.zero] * 3
        if Mo is not None:
            mom = g.vadd(mom, Mo)
        A = kb["A"]
        for k in range(3):
            Q = g.add(g.add(g.mul(A[k], mom[0]), g.mul(A[3 + k], mom[1])), g.mul(A[6 + k], mom[2]))
            self.scatter(ua + 3 + k, g.lin(sign, Q))

    def apply_load(self, tape, mk, slot, F, Mo, sign):
        s = self.s
        if slot < 0 or s.a["marker_body"][mk] < 0:
            return
        kb = s.body(s.slot_body(tape, slot))
        P = s.pos(tape, mk, slot) if F is not None and (kb["rigid"] or kb["planar"]) else None
        self.apply_at(tape, slot, P, F, Mo, sign)

    def _sforce(self, tape, f, mode, mi, mj):
        s, g = self.s, self.s.g
        mb = s.a["marker_body"]
        f = s.tape(tape)[f]
        si = -1 if mb[mi] < 0 else 0
        sj = -1 if mb[mj] < 0 else (0 if mb[mi] < 0 or mb[mi] == mb[mj] else 1)
        torque, action_only = mode & 1, mode & 2       # csrc/elements/sforce.c
        if torque or action_only:
            X = s.axes(tape, mj, sj)
            vec = [g.mul(f, X[3 * i + 2]) for i in range(3)]
            self.apply_load(tape, mi, si, None if torque else vec, vec if torque else None, 1.0)
            if not action_only:
                self.apply_load(tape, mj, sj, None, vec, -1.0)
            return
        rel = g.vsub(s.pos(tape, mi, si), s.pos(tape, mj, sj))
        # coincident markers: no load when f is 0, else not a number (csrc/elements/sforce.c)
        nan = g.const(float("nan"))
        n2 = g.dot(rel, rel)
        inv = g.ge(g.zero, n2, g.if3(f, nan, g.zero, nan), g.div(g.one, g.fn("sqrt", n2)))
        vec = [g.mul(g.mul(r, inv), f) for r in rel]
        self.apply_load(tape, mi, si, vec, None, 1.0)
        self.apply_load(tape, mj, sj, vec, None, -1.0)

    def _vforce(self, tape, fx, fy, fz, tx, ty, tz, mi, si, sj, r, sr):
        s, g = self.s, self.s.g
        slots = s.tape(tape)
        X = s.axes(tape, r, sr)

        def resolve(comps):
            out = []
            for i in range(3):
                v = g.zero
                for j in range(3):
                    v = g.add(v, g.mul(X[3 * i + j], slots[comps[j]]))
                out.append(v)
            return out
        F, T = resolve((fx, fy, fz)), resolve((tx, ty, tz))
        P = s.pos(tape, mi, si)
        self.apply_at(tape, -1 if s.a["marker_body"][mi] < 0 else si, P, F, T, 1.0)
        self.apply_at(tape, sj, P, F, T, -1.0)

    def hold_rate(self, tape, gn, gd, lam):
        """The reaction lam along d(g')/du, and its row g' + c lam (csrc/assembly.c
        ps_hold_rate)."""
        s = self.s
        self.rate_force(tape, gn, s.y[lam])
        self.res[lam] = s.g.add(gd, s.g.mul(s.par("compliance", lam), s.y[lam]))

    def hold_position(self, tape, gn, mu):
        """Row mu is g + c mu; each position row q_j of the tape's bodies gets -mu dg/dq_j
        (csrc/assembly.c ps_hold_position)."""
        s, g = self.s, self.s.g
        self.res[mu] = g.add(gn, g.mul(s.par("compliance", mu), s.y[mu]))
        for b in s.tape_bodies(tape):
            qa = s.body(b)["qa"]
            for j in range(7 if s.body(b)["rigid"] else 3):
                self.res[qa + j] = g.sub(self.res[qa + j],
                                         g.mul(s.y[mu], g.diff(gn, s.y[qa + j])))

    def _motion(self, tape, f, gd, gn, kind, lam, w, mu):
        s, g = self.s, self.s.g
        slots = s.tape(tape)
        gn, gd, f = slots[gn], slots[gd], slots[f]
        self.hold_rate(tape, gn, gd, lam)
        if kind == lib.PS_MOTION_V:
            self.res[lam] = g.sub(self.res[lam], f)
        elif kind == lib.PS_MOTION_D:
            self.hold_position(tape, gn, mu)
        else:
            self.res[lam] = g.sub(self.res[lam], s.y[w])
            self.res[w] = g.sub(s.yp[w], f)

    def _joint(self, tape, gn, gd, lam, mu):
        slots = self.s.tape(tape)
        self.hold_rate(tape, slots[gn], slots[gd], lam)
        if mu >= 0:                       # a coupler of rotations has none
            self.hold_position(tape, slots[gn], mu)

    # csrc/elements/coupler.c holds its relation as a joint equation
    _coupler = _joint

    def _gcon(self, tape, gn, gd, lam, mu):
        """csrc/elements/gcon.c: a joint equation, or g(q, u, t) at the velocity level (row
        g + c lam, lam along dg/du_j on every velocity the tape reads)."""
        if mu >= 0:
            return self._joint(tape, gn, gd, lam, mu)
        s, g = self.s, self.s.g
        gnode = s.tape(tape)[gn]
        self.res[lam] = g.add(gnode, g.mul(s.par("compliance", lam), s.y[lam]))
        for b in s.tape_bodies(tape):
            ua = s.body(b)["ua"]
            for i in range(s.nu(b)):
                self.scatter(ua + i, g.mul(s.y[lam], g.diff(gnode, s.y[ua + i])))

    def _turn(self, tape, w, s):
        """A tracked angle's row: the wrapped error w (csrc/elements/turn.c)."""
        self.res[s] = self.s.tape(tape)[w]

    # the iteration matrix ---------------------------------------------------------------
    def _jacobian(self):
        """(row, col, node) of dF/dy + cj dF/dyp, sorted by column then row."""
        s, g = self.s, self.s.g
        kind = {v: ("y", i) for i, v in enumerate(s.y)}
        kind.update({v: ("yp", i) for i, v in enumerate(s.yp)})
        entries = {}
        for row, r in enumerate(self.res):
            for v in sorted(g.deps[r]):
                if v == s.time:
                    continue
                which, col = kind[v]
                d = g.diff(r, v)
                if which == "yp":
                    d = g.mul(g.cj, d)
                if d == g.zero:
                    continue
                key = (col, row)
                entries[key] = g.add(entries[key], d) if key in entries else d
        return [(row, col, node) for (col, row), node in sorted(entries.items())]
