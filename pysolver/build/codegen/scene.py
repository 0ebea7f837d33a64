"""A compiled kernel's scene as scalar expression graphs: residual rows, iteration matrix
entries, sensor expressions and request channels.

It reads the same arrays and tapes the C interpreter runs (so both kernels evaluate one
definition of the scene) and mirrors csrc/kinematics.c, csrc/tape.c and csrc/residual.c step by
step, over :class:`~.sym.Graph` nodes instead of hyper-dual numbers. Body kinematics are built
once per body and shared by every element (the tapes recompute them per element); derivatives
are taken symbolically, so each entry carries only the directions it depends on.
"""
from ... import catalogue
from ...rotations import G_INDEX, G_SIGN
from ..bindings import lib
from .sym import Graph, Unsupported

# the catalogue's opcodes and measures by short name ("SIN", "DX"), and the one-argument
# functions as :class:`~.sym.Graph` functions
OP = {c[len("PS_OP_"):]: getattr(lib, c) for c in catalogue.OPCODES}
M = {c[len("PS_M_"):]: getattr(lib, c) for c in catalogue.MEASURE_CODES}
UNARY = {getattr(lib, f.c): f.name.lower() for f in catalogue.of_kind("math1")}

# e' = 1/2 G(e) w_body: G's entries as (index of e, sign), csrc/tape.c ps_rate_coeff
_GIDX, _GSGN = G_INDEX, G_SIGN


class Scene:
    """Symbolic residual, Jacobian, sensors and outputs of one compiled kernel.

    Parameters
    ----------
    arrays : dict
        The compiled scene's arrays (a kernel's, or one element's renumbered by
        :mod:`~.looped`).
    params : set of int
        The constants read at run time (``m->consts[k]``) rather than folded in: the sweep
        parameters' slots.
    limit : int, optional
        Most graph nodes (:class:`~.sym.Unsupported` beyond it).
    rotations_at_run_time : bool, optional
        Read the markers' axes in their body frames at run time (``m->marker_rot``) rather
        than fold them in (looped C, for parts whose markers differ only in orientation).
    """

    def __init__(self, arrays, params=(), limit=None, rotations_at_run_time=False):
        self.a = a = arrays
        self.g = Graph(limit)
        self.params = set(params)
        self.rot_par = rotations_at_run_time
        self.ny = int(a["ny"])
        self.cf = float(a["force_scale"])
        self._bodies = {}
        self._tapes = {}
        g = self.g
        self.time = g.var("t")
        self.y = [g.var("y", i) for i in range(self.ny)]
        self.yp = [g.var("yp", i) for i in range(self.ny)]

    # numbers ----------------------------------------------------------------------------
    def par(self, array, obj, comp=0):
        """Component `comp` of object `obj` in the model array `array`, read at run time."""
        return self.g.leaf("par", (array, obj, comp))

    def const(self, k):
        if k in self.params:
            return self.par("consts", k)
        return self.g.const(self.a["consts"][k])

    # bodies and markers (csrc/kinematics.c) ---------------------------------------------
    def body(self, b):
        got = self._bodies.get(b)
        if got is None:
            got = self._bodies[b] = self._body(b)
        return got

    def _body(self, b):
        g, a, y, yp = self.g, self.a, self.y, self.yp
        qa, ua = int(a["body_qadr"][b]), int(a["body_uadr"][b])
        k = {"r": y[qa:qa + 3], "v": y[ua:ua + 3], "acc": yp[ua:ua + 3],
             "rigid": a["body_type"][b] == lib.PS_BODY_RIGID, "qa": qa, "ua": ua,
             "planar": a["body_type"][b] == lib.PS_BODY_PLANAR, "u": y[ua:ua + 3]}
        if k["planar"]:
            return self._planar(b, k)
        if not k["rigid"]:
            return k
        e = y[qa + 3:qa + 7]
        p = {}
        for i in range(4):
            for j in range(i, 4):
                p[i, j] = p[j, i] = g.mul(e[i], e[j])
        inv = g.add(g.add(g.add(p[0, 0], p[1, 1]), p[2, 2]), p[3, 3])
        inv = g.div(g.one, inv)
        A = [None] * 9
        for i in range(3):
            j, kk, ii = (i + 1) % 3 + 1, (i + 2) % 3 + 1, i + 1
            A[4 * i] = g.sub(g.sub(g.add(p[0, 0], p[ii, ii]), p[j, j]), p[kk, kk])
        A[1] = g.lin(2.0, p[1, 2], -2.0, p[0, 3])
        A[3] = g.lin(2.0, p[1, 2], 2.0, p[0, 3])
        A[2] = g.lin(2.0, p[1, 3], 2.0, p[0, 2])
        A[6] = g.lin(2.0, p[1, 3], -2.0, p[0, 2])
        A[5] = g.lin(2.0, p[2, 3], -2.0, p[0, 1])
        A[7] = g.lin(2.0, p[2, 3], 2.0, p[0, 1])
        A = [g.mul(x, inv) for x in A]
        wb = y[ua + 3:ua + 6]
        k.update(e=e, A=A, wb=wb, w=self.mat_vec(A, wb), al=self.mat_vec(A, yp[ua + 3:ua + 6]))
        return k

    def _planar(self, b, k):
        """A planar body (csrc/kinematics.c planar_cache): origin (x, y, z0), axes
        Rz(rz) A0, velocity (vx, vy, 0), angular velocity (0, 0, wz)."""
        g, y, yp, qa, ua = self.g, self.y, self.yp, k["qa"], k["ua"]
        P = [self.par("body_plane", b, i) for i in range(10)]
        th = y[qa + 2]
        c, s = g.fn("cos", th), g.fn("sin", th)
        A = ([g.sub(g.mul(P[j], c), g.mul(P[3 + j], s)) for j in range(3)]
             + [g.add(g.mul(P[j], s), g.mul(P[3 + j], c)) for j in range(3)] + P[6:9])
        k.update(r=[y[qa], y[qa + 1], P[9]], v=[y[ua], y[ua + 1], g.zero],
                 acc=[yp[ua], yp[ua + 1], g.zero], A=A, w=[g.zero, g.zero, y[ua + 2]],
                 al=[g.zero, g.zero, yp[ua + 2]])
        return k

    def mat_vec(self, A, v):
        g = self.g
        return [g.add(g.add(g.mul(A[3 * i], v[0]), g.mul(A[3 * i + 1], v[1])),
                      g.mul(A[3 * i + 2], v[2])) for i in range(3)]

    def slot_body(self, tape, slot):
        return int(self.a["tbody_body"][self.a["tape_body_adr"][tape] + slot])

    def on_ground(self, mk, slot):
        return mk < 0 or slot < 0 or self.a["marker_body"][mk] < 0

    def on_point(self, mk):
        """Whether marker mk is on a point body (translated, never rotated)."""
        return self.a["body_type"][self.a["marker_body"][mk]] == lib.PS_BODY_POINT

    def offset(self, kb, mk):
        """A s: the marker's body-fixed offset rotated to global."""
        g, A = self.g, kb["A"]
        s = [self.par("marker_pos", mk, i) for i in range(3)]
        return [g.add(g.add(g.mul(s[0], A[3 * i]), g.mul(s[1], A[3 * i + 1])),
                      g.mul(s[2], A[3 * i + 2])) for i in range(3)]

    def pos(self, tape, mk, slot):
        g = self.g
        if self.on_ground(mk, slot):
            return [g.zero] * 3 if mk < 0 else [self.par("marker_pos", mk, i)
                                                 for i in range(3)]
        kb = self.body(self.slot_body(tape, slot))
        if self.on_point(mk):
            return [g.add(kb["r"][i], self.par("marker_pos", mk, i)) for i in range(3)]
        return g.vadd(kb["r"], self.offset(kb, mk))

    def axes(self, tape, mk, slot):
        """The marker's axes X (9, row-major: column j is axis j)."""
        g = self.g
        if self.on_ground(mk, slot) or self.on_point(mk):
            if mk < 0:
                return [g.one if i % 4 == 0 else g.zero for i in range(9)]
            return self.rotation(mk)
        A = self.body(self.slot_body(tape, slot))["A"]
        R = self.rotation(mk)
        return [g.add(g.add(g.mul(R[j], A[3 * i]), g.mul(R[3 + j], A[3 * i + 1])),
                      g.mul(R[6 + j], A[3 * i + 2])) for i in range(3) for j in range(3)]

    def rotation(self, mk):
        """The marker's axes in its body's frame (9, row-major), as numbers or run-time reads."""
        if self.rot_par:
            return [self.par("marker_rot", mk, j) for j in range(9)]
        return [self.g.const(v) for v in self.a["marker_rot"][9 * mk:9 * mk + 9]]

    def vel(self, tape, mk, slot):
        g = self.g
        if self.on_ground(mk, slot):
            return [g.zero] * 3
        kb = self.body(self.slot_body(tape, slot))
        if self.on_point(mk):
            return list(kb["v"])
        return g.vadd(kb["v"], g.cross(kb["w"], self.offset(kb, mk)))

    def body_vector(self, tape, mk, slot, key):
        if self.on_ground(mk, slot) or self.on_point(mk):
            return [self.g.zero] * 3
        return list(self.body(self.slot_body(tape, slot))[key])

    def acc(self, tape, mk, slot):
        g = self.g
        if self.on_ground(mk, slot):
            return [g.zero] * 3
        kb = self.body(self.slot_body(tape, slot))
        if self.on_point(mk):
            return list(kb["acc"])
        p = self.offset(kb, mk)
        w = kb["w"]
        return g.vadd(g.vadd(kb["acc"], g.cross(kb["al"], p)), g.cross(w, g.cross(w, p)))

    # tapes (csrc/tape.c) ----------------------------------------------------------------
    def tape(self, t):
        """The nodes of every slot of tape t."""
        got = self._tapes.get(t)
        if got is None:
            got = self._tapes[t] = self._run(t)
        return got

    def _run(self, t):
        g, a = self.g, self.a
        code = a["code"]
        width = lib.PS_INSTR_WIDTH
        start = int(a["tape_code_adr"][t])
        out = []
        for i in range(int(a["tape_len"][t])):
            ins = [int(v) for v in code[(start + i) * width:(start + i + 1) * width]]
            op, x = ins[0], ins[1:]
            s = out
            if op == OP["CONST"]:
                v = self.const(x[0])
            elif op == OP["TIME"]:
                v = self.time
            elif op == OP["ADD"]:
                v = g.add(s[x[0]], s[x[1]])
            elif op == OP["SUB"]:
                v = g.sub(s[x[0]], s[x[1]])
            elif op == OP["MUL"]:
                v = g.mul(s[x[0]], s[x[1]])
            elif op == OP["DIV"]:
                v = g.div(s[x[0]], s[x[1]])
            elif op == OP["POW"]:
                v = g.pow(s[x[0]], s[x[1]])
            elif op == OP["NEG"]:
                v = g.neg(s[x[0]])
            elif op in UNARY:
                v = g.fn(UNARY[op], s[x[0]])
            elif op == OP["CLAMP01"]:
                xx = s[x[0]]
                v = g.ge(g.zero, xx, g.zero, g.ge(xx, g.one, g.one, xx))
            elif op == OP["ATAN2"]:
                v = g.atan2(s[x[0]], s[x[1]])
            elif op == OP["MOD"]:
                p, q = s[x[0]], s[x[1]]
                v = g.sub(p, g.mul(g.fn("aint", g.div(p, q)), q))
            elif op == OP["MAX"]:
                v = g.ge(s[x[0]], s[x[1]], s[x[0]], s[x[1]])
            elif op == OP["MIN"]:
                v = g.ge(s[x[1]], s[x[0]], s[x[0]], s[x[1]])
            elif op == OP["SIGN"]:
                v = g.mul(g.mul(g.sgn(s[x[0]]), g.sgn(s[x[1]])), s[x[0]])
            elif op == OP["DIM"]:
                v = g.ge(s[x[1]], s[x[0]], g.zero, g.sub(s[x[0]], s[x[1]]))
            elif op == OP["IF"]:
                v = g.if3(s[x[0]], s[x[1]], s[x[2]], s[x[3]])
            elif op == OP["MEASURE"]:
                v = self.measure(t, x)
            elif op == OP["GDOT"]:
                v = self.gdot(t, s[x[0]])
            elif op == OP["AXDOT"]:
                X1, X2 = self.axes(t, x[0], x[4]), self.axes(t, x[2], x[5])
                v = self.dot_cols(X1, x[1], X2, x[3])
            elif op == OP["SENVAL"]:
                v = g.leaf("sv", x[0])
            elif op == OP["STEPC"]:
                v = g.step(x[5], 0, s[x[0]], [self.const(k) for k in x[1:5]])
            elif op == OP["STATE"]:
                v = self.y[x[0]]
            elif op == OP["USER"]:
                k, adr, nin, chan, entry = x[:5]
                inputs = [s[int(slot)] for slot in self.a["user_in"][adr:adr + nin]]
                v = g.user((entry, k, chan), inputs + [self.time])
            else:
                raise Unsupported(f"tape instruction {op}")
            out.append(v)
        return out

    def dot_cols(self, X, a, Y, b):
        g = self.g
        out = g.mul(X[a], Y[b])
        for r in (1, 2):
            out = g.add(out, g.mul(X[3 * r + a], Y[3 * r + b]))
        return out

    def project(self, t, v, k, ks, comp):
        if k < 0:
            return v[comp]
        X = self.axes(t, k, ks)
        return self._dot_col(v, X, comp)

    def _dot_col(self, v, X, col):
        g = self.g
        out = g.mul(v[0], X[col])
        for r in (1, 2):
            out = g.add(out, g.mul(v[r], X[3 * r + col]))
        return out

    def norm(self, v, value=None):
        """|v| (0 with zero derivatives at v = 0, as the tapes)."""
        g = self.g
        n2 = g.dot(v, v)
        return g.ge(g.zero, n2, g.zero, g.fn("sqrt", n2) if value is None else value(n2))

    def rel_velocity(self, t, x, rel):
        g = self.g
        vrel = g.vsub(self.vel(t, x[1], x[5]), self.vel(t, x[2], x[6]))
        if x[4] >= 0:
            wl = self.body_vector(t, x[4], x[8], "w")
            vrel = g.vsub(vrel, g.cross(wl, rel))
        return vrel

    def rel_acceleration(self, t, x, rel):
        g = self.g
        arel = g.vsub(self.acc(t, x[1], x[5]), self.acc(t, x[2], x[6]))
        if x[4] < 0:
            return arel
        vrel = self.rel_velocity(t, x, rel)
        wl = self.body_vector(t, x[4], x[8], "w")
        arel = g.vsub(arel, [g.mul(g.const(2.0), c) for c in g.cross(wl, vrel)])
        arel = g.vsub(arel, g.cross(wl, g.cross(wl, rel)))
        al = self.body_vector(t, x[4], x[8], "al")
        return g.vsub(arel, g.cross(al, rel))

    def measure(self, t, x):
        g, kind = self.g, x[0]
        if kind >= M["AX"]:
            Xi, Xj = self.axes(t, x[1], x[5]), self.axes(t, x[2], x[6])
            if kind == M["AX"]:
                p, q = g.neg(self.dot_cols(Xi, 2, Xj, 1)), self.dot_cols(Xi, 2, Xj, 2)
            elif kind == M["AY"]:
                p, q = self.dot_cols(Xi, 2, Xj, 0), self.dot_cols(Xi, 2, Xj, 2)
            else:
                p, q = self.dot_cols(Xi, 0, Xj, 1), self.dot_cols(Xi, 0, Xj, 0)
            return g.atan2(p, q)
        if kind >= M["WDTX"]:                 # csrc/tape.c: alpha_i - alpha_j, in frame l
            rel = g.vsub(self.body_vector(t, x[1], x[5], "al"),
                         self.body_vector(t, x[2], x[6], "al"))
            if x[4] >= 0:
                wrel = g.vsub(self.body_vector(t, x[1], x[5], "w"),
                              self.body_vector(t, x[2], x[6], "w"))
                rel = g.vsub(rel, g.cross(self.body_vector(t, x[4], x[8], "w"), wrel))
            return self.project(t, rel, x[3], x[7], kind - M["WDTX"])
        if kind >= M["WX"]:
            rel = g.vsub(self.body_vector(t, x[1], x[5], "w"), self.body_vector(t, x[2], x[6], "w"))
            return self.project(t, rel, x[3], x[7], kind - M["WX"])
        rel = g.vsub(self.pos(t, x[1], x[5]), self.pos(t, x[2], x[6]))
        if kind <= M["DZ"]:
            return self.project(t, rel, x[3], x[7], kind - M["DX"])
        if kind == M["DM"]:
            return self.norm(rel)
        if kind <= M["VM"]:
            vrel = self.rel_velocity(t, x, rel)
            if kind == M["VM"]:
                return self.norm(vrel)
            return self.project(t, vrel, x[3], x[7], kind - M["VX"])
        if kind == M["VR"]:
            vrel = self.rel_velocity(t, x, rel)
            dot = g.dot(vrel, rel)
            return self.norm(rel, lambda n2: g.div(dot, g.fn("sqrt", n2)))
        arel = self.rel_acceleration(t, x, rel)
        return self.project(t, arel, x[3], x[7], kind - M["ACCX"])

    def tape_bodies(self, t):
        adr, n = int(self.a["tape_body_adr"][t]), int(self.a["tape_nbody"][t])
        return [int(b) for b in self.a["tbody_body"][adr:adr + n]]

    def rate_coeff(self, gnode, b, i):
        """d(g')/du_i for u entry i of body b (csrc/tape.c ps_rate_coeff)."""
        g, kb = self.g, self.body(b)
        if i < 3:
            return g.diff(gnode, self.y[kb["qa"] + i])
        k, out = i - 3, g.zero
        for a in range(4):
            grad = g.diff(gnode, self.y[kb["qa"] + 3 + a])
            out = g.add(out, g.mul(g.const(0.5 * _GSGN[a][k]), g.mul(grad, kb["e"][_GIDX[a][k]])))
        return out

    def nu(self, b):
        return 6 if self.body(b)["rigid"] else 3   # a planar body's u: (vx, vy, wz)

    def gdot(self, t, gnode):
        g = self.g
        out = g.diff(gnode, self.time)
        for b in self.tape_bodies(t):
            kb = self.body(b)
            u = list(kb["v"]) + list(kb["wb"]) if kb["rigid"] else list(kb["u"])
            for i in range(self.nu(b)):
                out = g.add(out, g.mul(self.rate_coeff(gnode, b, i), u[i]))
        return out
