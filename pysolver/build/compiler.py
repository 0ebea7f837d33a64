"""Compile a validated Model into the flat arrays of the C kernel's psModel.

The state holds only what the scene has: per point body q = (x, y, z), u = (vx, vy, vz); per
rigid body q = (x, y, z, e0..e3), u = (vx, vy, vz) global and (wx, wy, wz) in the body frame.
Every expression becomes a tape: a register program over hyper-dual numbers whose basis is
the q entries of the bodies it touches, time, then their u (and u' for accelerations) entries;
second derivatives are kept for the q-and-time block only.

Longer than 400 lines because it is one lowering pass (expression trees to tape instructions,
with the layout and the per-element outputs it fills); split, the instruction set it emits
would be spread over several files.
"""
import math

import numpy as np

from .. import catalogue
from ..deck import expr as ex
from ..deck import joints, motions
from ..deck.expr import CONSTANTS
from ..deck.floating import placed
from ..deck.references import unwrapped_angles, velocity_level
from ..errors import DeckError
from ..records import law_key
from ..rotations import e_from_rot
from . import angles, energy, netforce, splines
from .bindings import lib
from .held import held_states, scene_held
from .planar import global_inertia as planar_global_inertia
from .planar import initial_state as planar_initial_state
from .planar import plane_rows as planar_plane_rows
from .planar import removed_rows as planar_removed_rows
from .planar import scene_planar

W = lib.PS_INSTR_WIDTH
# the catalogue's C enum names as the extension's values
_C = {name: getattr(lib, name) for name in catalogue.OPCODES + catalogue.MEASURE_CODES}
_ARITH = {op: _C[f.c] for op, f in catalogue.ARITHMETIC.items() if op != "neg"}
# constant folding of arithmetic (Python floats follow the same IEEE rules as the kernel)
_FOLD = {_C[f.c]: f.py for f in catalogue.ARITHMETIC.values() if f.fold}
# the force functions of the elements held as a vector force, and their elements
_LAWS = {"BUSH": "Force_Bushing", "FIELD": "Force_Field", "BEAM": "Force_Beam"}


def _key_ids(key):
    """The ids of a canonical user-subroutine input key such as "DM(9,1)"."""
    inner = key.partition("(")[2].rstrip(")")
    return [int(v) for v in inner.split(",") if v]


#: The constant that stands for TIME in a conservative (MKEAM) kernel: its motions hold
#: their place at the static command's time, with no rate.
FROZEN_TIME = "MKEAM/time"


class Layout:
    """Where each body's coordinates live in the state vector.

    ``planar``: the ids of the bodies integrated in planar coordinates (x, y, rz, vx, vy, wz),
    decided from the model (:func:`pysolver.build.planar.scene_planar`); a planar scene also
    leaves out its revolutes' out-of-plane equations. ``sizes``: each body's (nq, nu).
    ``held_axes``: {point body id: global axes nothing moves it along}, and ``held`` their
    states (:mod:`pysolver.build.held`), which IDA leaves out."""

    def __init__(self, model, removed=()):
        self.planar = scene_planar(model)
        self.held_axes = scene_held(model)
        removed = set(removed) | set(planar_removed_rows(model, self.planar))
        self.bodies = [b for _, b in sorted(model.bodies.items()) if b.kind != "ground"]
        self.index = {b.id: i for i, b in enumerate(self.bodies)}
        self.sizes = [(3, 3) if b.kind == "point" or b.id in self.planar else (7, 6)
                      for b in self.bodies]
        self.qadr, self.uadr, self.names = [], [], []
        off = 0
        for b, (nq, nu) in zip(self.bodies, self.sizes):
            self.qadr.append(off)
            self.uadr.append(off + nq)
            if b.id in self.planar:
                qn, un = ["x", "y", "rz"], ["vx", "vy", "wz"]
            else:
                qn = ["x", "y", "z"] + (["e0", "e1", "e2", "e3"] if nu == 6 else [])
                un = ["vx", "vy", "vz"] + (["wx", "wy", "wz"] if nu == 6 else [])
            self.names += [f"body{b.id}.{n}" for n in qn + un]
            off += nq + nu
        self.held = held_states(self, self.held_axes)
        # per Motion_Marker its reaction lam (an algebraic state); a displacement motion also
        # mu, which holds it at the position level, an acceleration motion the driven
        # velocity w, which integrates its expression; then per joint equation lam and mu, then
        # per Constraint_General. lam, rate (w) and mu are aligned: motions first, in id
        # order, then joints, then general constraints.
        self.motion_ids = sorted(model.motions)
        self.motion_tags = {m: "Motion_" + ("Joint" if model.motions[m].joint else "Marker")
                            for m in self.motion_ids}
        # each motion's (ic_disp, ic_vel) and whether it turns (ic_disp then an angle)
        self.motion_ic = [(model.motions[m].ic_disp, model.motions[m].ic_vel,
                           model.motions[m].direction.startswith("B")) for m in self.motion_ids]
        self.lam, self.rate, self.mu = [], [], []
        for mid in self.motion_ids:
            mo = model.motions[mid]
            self.lam.append(off)
            self.names.append(f"motion{mid}.reaction")
            off += 1
            self.rate.append(off if mo.val_type == "A" else -1)
            self.mu.append(off if mo.val_type == "D" else -1)
            if mo.val_type != "V":
                self.names.append(f"motion{mid}." + ("velocity" if mo.val_type == "A" else
                                                      "position_reaction"))
                off += 1
        # (kind, id, equation index) of each constraint equation, aligned with their lam:
        # joint_rows the joints' (jid, k), then the general constraints'; redundant equations
        # (`removed`, found by pysolver.build.consistent.redundant) are left out
        self.joint_rows, self.constraint_rows = [], []
        # the joint equations holding an angle between axes (their rates are angular rates)
        self.angular_rows = set()
        equations = [("joint", jid, len(catalogue.JOINT_EQUATIONS[model.joints[jid].type]))
                     for jid in sorted(model.joints)]
        equations += [("gcon", gid, 1) for gid in sorted(model.gcons)]
        equations += [("coupler", cid, 1) for cid in sorted(model.couplers)]
        # a Constraint_General of velocities is held at the velocity level alone (no mu)
        rate_only = {("gcon", g) for g, gc in model.gcons.items()
                     if velocity_level(gc)}
        for kind, jid, neq in equations:
            for k in range(neq):
                if (kind, jid, k) in removed:
                    continue
                self.constraint_rows.append((kind, jid, k))
                if kind == "joint":
                    self.joint_rows.append((jid, k))
                    eq = catalogue.JOINT_EQUATIONS[model.joints[jid].type][k][0]
                    if eq in ("dot", "dot2"):
                        self.angular_rows.add((kind, jid, k))
                held = (kind, jid) not in rate_only
                self.lam.append(off)
                self.mu.append(off + 1 if held else -1)
                self.rate.append(-1)
                self.names += ([f"joint{jid}.reaction{k + 1}",
                                f"joint{jid}.position_reaction{k + 1}"] if kind == "joint" else
                               [f"{kind}{jid}.reaction"]
                               + [f"{kind}{jid}.position_reaction"] * held)
                off += 1 + held
        # per angle tracked through its turns (a SCREW's or RACK_PINION's, a coupler's
        # rotation k, a rotational spring's, an expression's AX..AZ of a pair of markers) its
        # state s, algebraic: (owner kind, id, k) -> s
        self.turns = {}
        keys = [("joint", jid, 0) for jid in sorted(model.joints) if model.joints[jid].lead]
        keys += [("coupler", cid, k) for cid in sorted(model.couplers)
                 for k, f in enumerate(model.couplers[cid].freedoms) if f == "R"]
        keys += [("sforce", sid, 0) for sid in sorted(model.sforces) if model.sforces[sid].turns]
        keys += [("unwrap", call, 0) for call in unwrapped_angles(model)]
        for key in keys:
            self.turns[key] = off
            owner = (f"springdamper{-key[1]}" if key[0] == "sforce" else
                     "{}_{}_{}".format(*key[1]) if key[0] == "unwrap" else
                     f"{key[0]}{key[1]}")
            self.names.append(f"{owner}.angle" + (f"{key[2] + 1}" if key[0] == "coupler"
                                                  else ""))
            off += 1
        self.algebraic = sorted(self.lam + [m for m in self.mu if m >= 0]
                                + list(self.turns.values()))
        self.ny = off

    def initial_state(self):
        """The state at t = 0 from the bodies' current initial conditions (a sweep case may
        change them between runs)."""
        y = np.zeros(self.ny)
        for b, qa, ua in zip(self.bodies, self.qadr, self.uadr):
            if b.id in self.planar:
                y[qa:qa + 3], y[ua:ua + 3] = planar_initial_state(b)
                continue
            y[qa:qa + 3] = b.pos
            y[ua:ua + 3] = b.vel
            if b.kind == "rigid":
                y[qa + 3:qa + 7] = self._euler(b)
                y[ua + 3:ua + 6] = b.omega
        return y

    def _euler(self, b):
        """Euler parameters of a body's initial rotation, kept while the rotation is the same
        (e_from_rot is a quarter of a short run's Python)."""
        key = np.asarray(b.rot, dtype=float).tobytes()
        got = self.__dict__.setdefault("_euler_of", {}).get(b.id)
        if got is None or got[0] != key:
            got = self._euler_of[b.id] = (key, e_from_rot(b.rot))
        return got[1]


def _number(node):
    """The value of a tree that is a number (or a negated one), else None."""
    if node[0] == "num":
        return node[1]
    if node[0] == "neg" and node[1][0] == "num":
        return -node[1][1]
    return None


class _Tape:
    """Builds one tape; instructions are hash-consed so shared subexpressions run once."""

    def __init__(self, comp):
        self.c = comp
        self.code = []
        self.memo = {}
        self.bodies = []          # [body index, need_u, need_a]
        self.slot_of = {}
        self.touch = []           # stack of sets of body slots touched
        self.has_gdot = False
        self.second_in_u = False     # a velocity-level constraint: d2g/du dq, d2g/du du
        self.uses_senval = False
        self.states = []          # y entries read with their derivative (PS_OP_STATE)

    def body_slot(self, bidx, need_u=False, need_a=False):
        if bidx not in self.slot_of:
            self.slot_of[bidx] = len(self.bodies)
            self.bodies.append([bidx, False, False, False])
        s = self.slot_of[bidx]
        self.bodies[s][1] |= need_u or need_a
        self.bodies[s][2] |= need_a
        self.bodies[s][3] |= need_u or need_a     # global angular velocity (measures only)
        for t in self.touch:
            t.add(s)
        return s

    def emit(self, op, *args):
        row = (op,) + tuple(args) + (0,) * (W - 1 - len(args))
        if row in self.memo:
            return self.memo[row]
        self.code.append(row)
        self.memo[row] = len(self.code) - 1
        return self.memo[row]

    def const(self, v):
        return self.emit(lib.PS_OP_CONST, self.c.const_index(float(v)))

    def value(self, slot):
        """The constant value of a slot, or None when it is not a constant (a parameter a
        batch study may change is not)."""
        row = self.code[slot]
        if row[0] != lib.PS_OP_CONST or row[1] in self.c.param_slots:
            return None
        return self.c.consts[row[1]]

    def param(self, path, v):
        """A number of the model a case of a sweep may change (pysolver.build.params): a
        constant slot of its own, never folded."""
        return self.emit(lib.PS_OP_CONST, self.c.param_index(path, v))

    def op(self, op, *slots):
        vals = [self.value(s) for s in slots]
        if op in _FOLD and all(v is not None for v in vals):
            return self.const(_FOLD[op](*vals))
        if op == lib.PS_OP_POW:
            return self.emit(op, slots[0], slots[1], int(vals[1] is not None))
        return self.emit(op, *slots)

    # smoothing functions, built from elementary operations on slots
    def ramp(self, x, x0, x1):
        w = self.op(lib.PS_OP_SUB, x1, x0)
        d = self.op(lib.PS_OP_DIV, self.op(lib.PS_OP_SUB, x, x0), w)
        # bounds that meet make the ramp NaN for every x, not a jump clamped to 0 or 1 (the
        # kernel then names the element): 1/w - 1/w is exactly 0, with zero derivatives,
        # while w is not 0, and NaN where it is
        inv = self.op(lib.PS_OP_DIV, self.const(1), w)
        d = self.op(lib.PS_OP_ADD, d, self.op(lib.PS_OP_SUB, inv, inv))
        return self.emit(lib.PS_OP_CLAMP01, d)

    def step_const(self, x, x0, h0, x1, h1, kind="STEP"):
        """STEP-family function of slot x between constant points (numbers, or (path, value)
        parameters): one instruction."""
        idx = [self.c.param_index(*v) if isinstance(v, tuple) else self.c.const_index(float(v))
               for v in (x0, h0, x1, h1)]
        return self.emit(lib.PS_OP_STEPC, x, *idx, catalogue.STEP_SHAPES.index(kind))

    def step(self, x, x0, h0, x1, h1, kind="STEP"):
        bounds = [self.value(s) for s in (x0, h0, x1, h1)]
        if all(v is not None for v in bounds) and bounds[0] != bounds[2]:
            # the common case (literal bounds): one instruction instead of about ten
            return self.step_const(x, *bounds, kind=kind)
        D = self.ramp(x, x0, x1)
        dh = self.op(lib.PS_OP_SUB, h1, h0)
        mul, add, sub = lib.PS_OP_MUL, lib.PS_OP_ADD, lib.PS_OP_SUB
        if kind == "STEP":      # D^2 (3 - 2D)
            shape = self.op(mul, self.op(mul, D, D),
                            self.op(sub, self.const(3), self.op(mul, self.const(2), D)))
        elif kind == "STEP5":   # D^3 (10 - 15 D + 6 D^2)
            poly = self.op(add, self.op(sub, self.const(10), self.op(mul, self.const(15), D)),
                           self.op(mul, self.const(6), self.op(mul, D, D)))
            shape = self.op(mul, self.op(mul, self.op(mul, D, D), D), poly)
        else:                   # HAVSIN: (1 + sin(pi D - pi/2)) / 2
            arg = self.op(sub, self.op(mul, self.const(math.pi), D), self.const(math.pi / 2))
            shape = self.op(mul, self.const(0.5), self.op(add, self.const(1),
                                                           self.emit(lib.PS_OP_SIN, arg)))
        return self.op(add, h0, self.op(mul, dh, shape))



class Compiler:
    """Turns a Model into psModel arrays (see csrc/include/pysolver.h)."""

    def __init__(self, model, conservative=False, removed=()):
        self.model = model
        self.conservative = conservative   # MKEAM: velocity-dependent terms (damping) removed
        self.layout = Layout(model, removed)
        self.consts, self._cidx = [], {}
        self.params, self.param_slots = {}, set()   # sweep parameters: path -> const slot
        self.markers = sorted(model.markers)
        self.midx = {mid: i for i, mid in enumerate(self.markers)}
        self.tapes = []
        self.stack = []
        self.eidx = {eid: i for i, eid in enumerate(sorted(model.evaluates))}
        self.user_in, self._user_in_adr = [], {}   # input slots of PS_OP_USER instructions
        self._user_cache = {}                      # PS_OP_USER rows -> their cache entry

    def param_index(self, path, v):
        """The constant slot of parameter `path` (one per path, whatever its value)."""
        if path not in self.params:
            self.params[path] = len(self.consts)
            self.param_slots.add(len(self.consts))
            self.consts.append(float(v))
        return self.params[path]

    def const_index(self, v):
        key = v if not math.isnan(v) else "nan"
        if key not in self._cidx:
            self._cidx[key] = len(self.consts)
            self.consts.append(v)
        return self._cidx[key]

    # lowering of parse trees -------------------------------------------------------------
    def placed(self, mid):
        """The marker whose frame marker `mid` is in a measure: a floating marker's I marker
        (deck.floating: the vector forces that use it keep it there), else `mid` itself."""
        return placed(self.model, mid)

    def marker(self, tape, mid, need_u=False, need_a=False):
        """Return (marker index, body slot) for marker id `mid`; id 0 is the global frame."""
        if not mid:
            return -1, -1
        m = self.model.markers[mid]
        body = self.model.bodies[m.body]
        if body.kind == "ground":
            return self.midx[mid], -1
        return self.midx[mid], tape.body_slot(self.layout.index[body.id], need_u, need_a)

    def lower(self, tape, node):
        tag = node[0]
        if tag == "user":
            return self.user_call(tape, *node[1:])
        if tag == "ctrl":                 # a LoadControl's velocity: stored after SENVALs
            return tape.emit(lib.PS_OP_SENVAL, len(self.eidx) + node[1])
        if tag == "num":
            return tape.const(node[1])
        if tag == "param":                # a number of the model sweeps may change
            return tape.param(node[1], node[2])
        if tag == "turned":               # an angle unwrapped by its tracked state
            s, w = self.turn_error(tape, node[1], node[2])
            return tape.op(lib.PS_OP_ADD, s, w)
        if tag == "axdot":                # a joint's dot product of two markers' axes
            mi, si = self.marker(tape, node[1])
            mj, sj = self.marker(tape, node[3])
            return tape.emit(lib.PS_OP_AXDOT, mi, node[2], mj, node[4], si, sj)
        if tag == "name":
            if node[1] == "TIME" and self.conservative:
                return tape.param(FROZEN_TIME, 0.0)   # MKEAM's time stands still
            if node[1] == "TIME":
                return tape.emit(lib.PS_OP_TIME)
            return tape.const(CONSTANTS[node[1]])
        if tag == "neg":
            return tape.op(lib.PS_OP_NEG, self.lower(tape, node[1]))
        if tag == "bin":
            return tape.op(_ARITH[node[1]], self.lower(tape, node[2]), self.lower(tape, node[3]))
        name, args = node[1], node[2]
        f = catalogue.FUNCTIONS[name]
        if name in ex.TRACKED_ANGLES:     # AXU..AZU: through every turn
            ids = [self.placed(int(a[1])) for a in args] + [0]
            key = ("unwrap", (name[:2], ids[0], ids[1]), 0)
            s, w = self.turn_error(tape, self.turned_angle(key), key)
            return tape.op(lib.PS_OP_ADD, s, w)
        if f.kind == "measure":
            return self.measure(tape, name, [int(a[1]) for a in args])
        if name == "VARVAL":
            vid = int(args[0][1])
            expr = self.model.variables[vid].expr
            number = _number(expr)
            if number is not None:        # a named number: a parameter of sweeps
                return tape.param(f"Reference_Variable/{vid}/value", number)
            return self.lower(tape, expr)
        if name == "PFORCE":
            return self.penalty_force(tape, int(args[0][1]))[1]
        if name == "SFORCE":
            return self.sforce_measure(tape, *(int(a[1]) for a in args))
        if name == "SPDP":                # a spring-damper is a scalar force under -id
            sid, *rest = (int(a[1]) for a in args)
            return self.sforce_measure(tape, -sid, *rest)
        if name in _LAWS:                 # a bushing, field or beam is a vector force
            eid, *rest = (int(a[1]) for a in args)
            return self.vforce_measure(tape, law_key(_LAWS[name], eid), *rest)
        if name == "MOTION":
            return self.motion_measure(tape, *(int(a[1]) for a in args))
        if name == "JOINT":
            return self.joint_measure(tape, *(int(a[1]) for a in args))
        if name in angles.NAMES:
            return angles.lower_angle(self, tape, name, [self.placed(int(a[1])) for a in args])
        if name in catalogue.MAGNITUDES:
            return self.magnitude(tape, name, [int(a[1]) for a in args])
        if name in splines.NAMES:
            spline = self.model.splines[int(args[2][1])]
            x = self.lower(tape, args[0])
            if spline.z:
                return splines.lower_surface(self, tape, name, x, self.lower(tape, args[1]),
                                             spline)
            return splines.lower_spline(self, tape, name, x, spline,
                                        int(args[3][1]) if len(args) > 3 else 0)
        if name in netforce.NAMES:
            return netforce.lower_net(self, tape, name, [int(a[1]) for a in args])
        if name == "ORIENT":
            system, k, *ids = [int(a[1]) for a in args]
            return angles.lower_orient(self, tape, system, k, *map(self.placed, ids))
        if name == "KE":
            return energy.lower_energy(self, tape, int(args[0][1]))
        if name == "SENVAL":
            tape.uses_senval = True
            return tape.emit(lib.PS_OP_SENVAL, self.eidx[int(args[0][1])])
        slots = [self.lower(tape, a) for a in args]
        if f.kind == "step":
            return tape.step(*slots, kind=name)
        if f.c is not None:               # one instruction: math functions, IF
            return tape.op(_C[f.c], *slots)
        # functions built from other instructions: IMPACT, BISTOP
        return getattr(self, name.lower())(tape, *slots)

    def turn_error(self, tape, angle, key):
        """(s, w): the tracked angle `key`'s state s, read on the tape, and w = the measured
        `angle` less s, wrapped to (-pi, pi] (csrc/elements/turn.c holds w at zero)."""
        state = self.layout.turns[key]
        if state not in tape.states:
            tape.states.append(state)
        s = tape.emit(lib.PS_OP_STATE, state, tape.states.index(state))
        e = tape.op(lib.PS_OP_SUB, self.lower(tape, angle), s)
        return s, tape.op(lib.PS_OP_ATAN2, tape.op(lib.PS_OP_SIN, e), tape.op(lib.PS_OP_COS, e))

    def user_call(self, tape, k, channel, inputs):
        """A user subroutine on its declared inputs (csrc/usersub.c)."""
        slots = tuple(self.lower(tape, a) for a in inputs)
        key = (id(tape), slots)
        if key not in self._user_in_adr:
            self._user_in_adr[key] = len(self.user_in)
            self.user_in.extend(slots)
        adr = self._user_in_adr[key]
        # one cache entry per distinct instruction (emit shares identical rows)
        row = (id(tape), k, adr, channel)
        cache = self._user_cache.setdefault(row, len(self._user_cache))
        return tape.emit(lib.PS_OP_USER, k, adr, len(slots), channel, cache)

    def magnitude(self, tape, name, ids):
        """WM, ACCM, WDTM: the norm of the three components in the global axes; 0, with zero
        derivatives, where they all vanish (as DM and VM in C)."""
        f = catalogue.FUNCTIONS[name]
        roles = dict(zip(f.args, ids))
        total = None
        for comp in catalogue.MAGNITUDES[name]:
            c = self.measure(tape, comp, [roles.get(r, 0) if r != "k" else 0
                                          for r in catalogue.FUNCTIONS[comp].args])
            sq = tape.op(lib.PS_OP_MUL, c, c)
            total = sq if total is None else tape.op(lib.PS_OP_ADD, total, sq)
        return netforce.norm_slot(tape, total)

    def measure(self, tape, name, ids):
        f = catalogue.FUNCTIONS[name]
        need_u = "velocities" in f.reads
        need_a = "accelerations" in f.reads
        if self.conservative and need_u:
            return tape.const(0.0)
        # the markers by role: i, j, k (the axes of the components), l (the frame of time
        # derivatives); 0 is the global frame
        roles = dict(zip(f.args, ids))
        ids = [self.placed(roles.get(r, 0)) for r in "ijkl"]
        mk, sl = [], []
        for k, mid in enumerate(ids):
            u = need_u if k != 2 else False
            i, s = self.marker(tape, mid, u, need_a if k != 2 else False)
            mk.append(i)
            sl.append(s)
        return tape.emit(lib.PS_OP_MEASURE, _C[f.c], *mk, *sl)

    def impact(self, t, x, xd, x1, k, e, cmax, d):
        """IMPACT: k (x1 - x)^e - STEP(x, x1 - d, cmax, x1, 0) xd, at least 0, for x < x1."""
        sub, mul = lib.PS_OP_SUB, lib.PS_OP_MUL
        pen = t.op(lib.PS_OP_POW, t.op(sub, x1, x), e)
        damp = t.op(mul, t.step(x, t.op(sub, x1, d), cmax, x1, t.const(0)), xd)
        f = t.emit(lib.PS_OP_MAX, t.const(0), t.op(sub, t.op(mul, k, pen), damp))
        zero = t.const(0)
        return t.emit(lib.PS_OP_IF, t.op(sub, x, x1), f, zero, zero)

    def bistop(self, t, x, xd, x1, x2, k, e, cmax, d):
        """BISTOP: IMPACT-like walls at x1 (pushing up) and x2 (pushing down)."""
        sub, mul, add = lib.PS_OP_SUB, lib.PS_OP_MUL, lib.PS_OP_ADD
        zero = t.const(0)
        low = t.op(sub, t.op(mul, k, t.op(lib.PS_OP_POW, t.op(sub, x1, x), e)),
                   t.op(mul, t.step(x, t.op(sub, x1, d), cmax, x1, zero), xd))
        low = t.emit(lib.PS_OP_MAX, low, zero)
        spring = t.op(mul, k, t.op(lib.PS_OP_POW, t.op(sub, x, x2), e))
        high = t.op(sub, t.op(lib.PS_OP_NEG, spring),
                    t.op(mul, t.step(x, x2, zero, t.op(add, x2, d), cmax), xd))
        high = t.emit(lib.PS_OP_MIN, high, zero)
        upper = t.emit(lib.PS_OP_IF, t.op(sub, x, x2), zero, zero, high)
        return t.emit(lib.PS_OP_IF, t.op(sub, x, x1), low, zero, upper)

    def _guard(self, key):
        if key in self.stack:
            chain = " -> ".join(f"{k} {i}" for k, i in self.stack + [key])
            raise DeckError(f"force measure cycle: {chain}", file=self.model.source.file,
                            element=key[0], id=key[1])
        self.stack.append(key)

    def lower_for_rate(self, tape, tree):
        """Lower a displacement expression g whose total time derivative g' (PS_OP_GDOT) the
        tape will take: the velocities of the bodies g reads become part of its basis."""
        touched = set()
        tape.touch.append(touched)
        g = self.lower(tape, tree)
        tape.touch.pop()
        for s in touched:
            tape.bodies[s][1] = True
        return g

    def penalty_force(self, tape, pid):
        """Return slots (g, F) of Force_Penalty `pid`: F = -p g - p1 g', smoothed if unilateral."""
        self._guard(("Force_Penalty", pid))
        p = self.model.penalties[pid]
        g = self.lower_for_rate(tape, p.expr)
        mul, add = lib.PS_OP_MUL, lib.PS_OP_ADD
        where = f"Force_Penalty/{pid}"
        gd = None
        if p.penalty1 > 0 and not self.conservative:
            gd = tape.emit(lib.PS_OP_GDOT, g)
            tape.has_gdot = True
        if p.unilateral:
            S = tape.step_const(g, 0.0, 0.0, (f"{where}/smoothing_factor", p.smoothing), 1.0)
            k = tape.op(mul, tape.param(f"{where}/penalty", p.penalty), S)
            c = tape.op(mul, tape.param(f"{where}/penalty1", p.penalty1), S) \
                if gd is not None else None
        else:
            k = tape.param(f"{where}/penalty", p.penalty)
            c = tape.param(f"{where}/penalty1", p.penalty1) if gd is not None else None
        f = tape.op(mul, k, g)
        if gd is not None:
            f = tape.op(add, f, tape.op(mul, c, gd))
        self.stack.pop()
        return g, tape.op(lib.PS_OP_NEG, f)

    def sforce_measure(self, tape, sid, jflag, comp, rm):
        """SFORCE(id, jflag, comp, rm): 1 |force|, 2-4 force in rm, 5 |torque|, 6-8 torque."""
        self._guard(("Force_Scalar_TwoBody", sid))
        sf = self.model.sforces[sid]
        f = self.lower(tape, sf.expr)
        sign = -1.0 if jflag else 1.0
        mul = lib.PS_OP_MUL
        if (comp >= 5) != sf.torque or (jflag and sf.action_only):
            out = tape.const(0)                   # an action-only force has no reaction
        elif comp in (1, 5):
            out = tape.op(lib.PS_OP_ABS, f)
        elif not sf.torque and not sf.action_only:
            name = "DX DY DZ".split()[comp - 2]
            along = tape.op(lib.PS_OP_DIV, self.measure(tape, name, [sf.i, sf.j, rm]),
                            self.measure(tape, "DM", [sf.i, sf.j]))
            out = tape.op(mul, tape.const(sign), tape.op(mul, f, along))
        else:
            mj, sj = self.marker(tape, sf.j)
            mr, sr = self.marker(tape, self.placed(rm))
            ax = tape.emit(lib.PS_OP_AXDOT, mj, 2, mr, (comp - 2) % 4, sj, sr)
            out = tape.op(mul, tape.const(sign), tape.op(mul, f, ax))
        self.stack.pop()
        return out

    def vforce_measure(self, tape, vid, jflag, comp, rm):
        """A vector force's force (comp 1-4) or torque (5-8) on I's body at I (jflag 0), or on
        the J marker's body at that marker (1: -F, and -T - d x F with d = oI - oJ; -F and -T
        at a floating J, which the force keeps on I: deck.floating), in rm's axes (BUSH(),
        FIELD() and BEAM() of the elements held as one)."""
        vf = self.model.vforces[vid]
        mul, add, sub = lib.PS_OP_MUL, lib.PS_OP_ADD, lib.PS_OP_SUB
        mref, sref = self.marker(tape, vf.ref)
        mr, sr = self.marker(tape, self.placed(rm))
        comps = [self.lower(tape, e) for e in vf.exprs]

        def resolved(vals):
            # sum_j f_j (axis j of ref) . (axis c of rm), for c = x, y, z
            out = []
            for c in range(3):
                v = tape.const(0.0)
                for j in range(3):
                    v = tape.op(add, v, tape.op(mul, vals[j], tape.emit(
                        lib.PS_OP_AXDOT, mref, j, mr, c, sref, sr)))
                out.append(v)
            return out
        force, torque = resolved(comps[:3]), resolved(comps[3:])
        if jflag and vid > 0 and vf.j and self.model.markers[vf.j].floating:
            # the reaction at the floating marker, which the force keeps on I: -F, -T
            minus = tape.const(-1.0)
            torque = [tape.op(mul, minus, t) for t in torque]
            force = [tape.op(mul, minus, f) for f in force]
        elif jflag:
            d = [self.measure(tape, n, [vf.i, vf.j, rm]) for n in ("DX", "DY", "DZ")]
            dxf = [tape.op(sub, tape.op(mul, d[(c + 1) % 3], force[(c + 2) % 3]),
                           tape.op(mul, d[(c + 2) % 3], force[(c + 1) % 3])) for c in range(3)]
            minus = tape.const(-1.0)
            torque = [tape.op(mul, minus, tape.op(add, t, x)) for t, x in zip(torque, dxf)]
            force = [tape.op(mul, minus, f) for f in force]
        if comp in (2, 3, 4):
            return force[comp - 2]
        if comp in (6, 7, 8):
            return torque[comp - 6]
        parts = force if comp == 1 else torque
        total = tape.op(add, tape.op(mul, parts[0], parts[0]),
                        tape.op(add, tape.op(mul, parts[1], parts[1]),
                                tape.op(mul, parts[2], parts[2])))
        return netforce.norm_slot(tape, total)

    def motion_measure(self, tape, mid, jflag=None, comp=None, rm=0):
        """MOTION(id): the reaction along (about) the motion's axis of J; MOTION(id, jflag,
        comp, rm): 1 |force|, 2-4 force in rm, 5 |torque|, 6-8 torque on I (jflag 0) or J
        (jflag 1). A translation's force acts at I: no torque on I, on J the torque of the
        opposite force about J. A Motion_Joint's rotation torque is along J's z axis; a
        Motion_Marker's B1..B3 torque is lam eps_k, the dual basis of the 1-2-3 sequence's
        axes (e1 = xJ, e2 = zI x xJ / c, e3 = zI; s = e1 . e3 = sin B2, c = cos B2):
        eps1 = (e1 - s e3) / c^2, eps2 = e2, eps3 = (e3 - s e1) / c^2, the torque whose
        power is lam times the angle's rate (the kernel applies lam d(g')/du)."""
        k = self.layout.motion_ids.index(mid)
        lam = self.layout.lam[k]
        if lam not in tape.states:
            tape.states.append(lam)
        L = tape.emit(lib.PS_OP_STATE, lam, tape.states.index(lam))
        if jflag is None:
            return L
        mo = self.model.motions[mid]
        rot = mo.direction.startswith("B")
        axis = int(mo.direction[1]) - 1 if rot else "XYZ".index(mo.direction)
        mul, sub = lib.PS_OP_MUL, lib.PS_OP_SUB
        mj, sj = self.marker(tape, mo.j)
        mr, sr = self.marker(tape, self.placed(rm))
        signed = tape.op(mul, tape.const(-1.0 if jflag else 1.0), L)
        # the force (translation) or torque (rotation) in rm's axes
        if rot and not mo.joint:
            vec = [tape.op(mul, signed, e) for e in self._euler_dual(tape, mo, axis, mr, sr)]
        else:
            vec = [tape.op(mul, signed, tape.emit(lib.PS_OP_AXDOT, mj, axis, mr, c, sj, sr))
                   for c in range(3)]
        zero = tape.const(0.0)
        if rot:
            force, torque = [zero] * 3, vec
        elif jflag:
            d = [self.measure(tape, n, [mo.i, mo.j, rm]) for n in ("DX", "DY", "DZ")]
            force = vec
            torque = [tape.op(sub, tape.op(mul, d[(c + 1) % 3], vec[(c + 2) % 3]),
                              tape.op(mul, d[(c + 2) % 3], vec[(c + 1) % 3])) for c in range(3)]
        else:
            force, torque = vec, [zero] * 3
        if comp in (2, 3, 4):
            return force[comp - 2]
        if comp in (6, 7, 8):
            return torque[comp - 6]
        parts = force if comp == 1 else torque
        total = tape.op(lib.PS_OP_ADD, tape.op(mul, parts[0], parts[0]),
                        tape.op(lib.PS_OP_ADD, tape.op(mul, parts[1], parts[1]),
                                tape.op(mul, parts[2], parts[2])))
        return netforce.norm_slot(tape, total)

    def _euler_dual(self, tape, mo, k, mr, sr):
        """Components in marker mr's axes of eps_k (k from 0), the dual basis vector of
        Motion_Marker mo's 1-2-3 angle B(k+1) (:meth:`motion_measure`)."""
        mul, sub = lib.PS_OP_MUL, lib.PS_OP_SUB
        mi, si = self.marker(tape, mo.i)
        mj, sj = self.marker(tape, mo.j)
        e1 = [tape.emit(lib.PS_OP_AXDOT, mj, 0, mr, c, sj, sr) for c in range(3)]
        e3 = [tape.emit(lib.PS_OP_AXDOT, mi, 2, mr, c, si, sr) for c in range(3)]
        s = tape.emit(lib.PS_OP_AXDOT, mi, 2, mj, 0, si, sj)
        c2 = tape.op(sub, tape.const(1.0), tape.op(mul, s, s))
        if k == 1:                        # (e3 x e1) / c
            c = tape.op(lib.PS_OP_SQRT, c2)
            return [tape.op(lib.PS_OP_DIV, tape.op(sub, tape.op(mul, e3[(n + 1) % 3],
                                                                 e1[(n + 2) % 3]),
                                                   tape.op(mul, e3[(n + 2) % 3],
                                                           e1[(n + 1) % 3])), c)
                    for n in range(3)]
        a, b = (e1, e3) if k == 0 else (e3, e1)
        return [tape.op(lib.PS_OP_DIV, tape.op(sub, a[n], tape.op(mul, s, b[n])), c2)
                for n in range(3)]

    def joint_measure(self, tape, jid, jflag, comp, rm):
        """JOINT(id, jflag, comp, rm): comp 1 |force|, 2-4 force, 5 |torque|, 6-8 torque of
        :meth:`joint_reaction`."""
        force, torque = self.joint_reaction(tape, jid, jflag, rm)
        if comp in (2, 3, 4):
            return force[comp - 2]
        if comp in (6, 7, 8):
            return torque[comp - 6]
        parts = force if comp == 1 else torque
        mul, add = lib.PS_OP_MUL, lib.PS_OP_ADD
        total = tape.op(add, tape.op(mul, parts[0], parts[0]),
                        tape.op(add, tape.op(mul, parts[1], parts[1]),
                                tape.op(mul, parts[2], parts[2])))
        return netforce.norm_slot(tape, total)

    def joint_reaction(self, tape, jid, jflag, rm):
        """(force, torque) slots of a joint, from its multipliers lam_k (the kernel applies
        lam_k d(g_k')/du): a d equation pushes I's body along its global axis, a dJ equation
        along J's axis, both at I's origin; a dot equation a_I . b_J turns it by
        lam (a_I x b_J) (and its symmetric twin for CONSTANT_VELOCITY). J's body gets the
        opposite force and the opposite torque less d x F about its origin (d = oI - oJ).
        Components in rm's axes; an equation removed as redundant carries nothing."""
        jo = self.model.joints[jid]
        mul, add, sub = lib.PS_OP_MUL, lib.PS_OP_ADD, lib.PS_OP_SUB
        mr, sr = self.marker(tape, self.placed(rm))
        ends = {"I": self.marker(tape, jo.i), "J": self.marker(tape, jo.j),
                "G": self.marker(tape, 0)}

        def axis(end, a):
            m, s = ends[end]
            return [tape.emit(lib.PS_OP_AXDOT, m, a, mr, c, s, sr) for c in range(3)]

        def cross(u, v):
            return [tape.op(sub, tape.op(mul, u[(c + 1) % 3], v[(c + 2) % 3]),
                            tape.op(mul, u[(c + 2) % 3], v[(c + 1) % 3])) for c in range(3)]

        def plus(u, v, scale=None):
            v = v if scale is None else [tape.op(mul, scale, x) for x in v]
            return [tape.op(add, a, b) for a, b in zip(u, v)]
        zero = tape.const(0.0)
        force, torque = [zero] * 3, [zero] * 3
        eqs = catalogue.JOINT_EQUATIONS[jo.type]
        for (owner, k), lam in zip(self.layout.joint_rows,
                                   self.layout.lam[len(self.layout.motion_ids):]):
            if owner != jid:
                continue
            if lam not in tape.states:
                tape.states.append(lam)
            L = tape.emit(lib.PS_OP_STATE, lam, tape.states.index(lam))
            eq = eqs[k]
            if eq[0] in ("d", "dJ"):
                force = plus(force, axis("G" if eq[0] == "d" else "J", eq[1]), L)
            elif eq[0] == "lead":
                # d . zJ - lead theta: along zJ at I, and -lead L dtheta/dw_I, with
                # theta = atan2(S, C), S = sign a_I . b_J, C = c_I . d_J:
                # dtheta/dw_I = (C sign (a_I x b_J) - S (c_I x d_J)) / (S^2 + C^2)
                _, a, b, sign, c, d = eq
                force = plus(force, axis("J", 2), L)
                dot = [tape.emit(lib.PS_OP_AXDOT, ends["I"][0], p, ends["J"][0], q,
                                 ends["I"][1], ends["J"][1]) for p, q in ((a, b), (c, d))]
                S, C = tape.op(mul, tape.const(sign), dot[0]), dot[1]
                norm = tape.op(add, tape.op(mul, S, S), tape.op(mul, C, C))
                scale = tape.op(lib.PS_OP_DIV, tape.op(mul, tape.const(-jo.lead), L), norm)
                rate = plus([tape.op(mul, tape.op(mul, tape.const(sign), C), x)
                             for x in cross(axis("I", a), axis("J", b))],
                            cross(axis("I", c), axis("J", d)), tape.op(lib.PS_OP_NEG, S))
                torque = plus(torque, rate, scale)
            else:
                turn = cross(axis("I", eq[1]), axis("J", eq[2]))
                if eq[0] == "dot2":
                    turn = plus(turn, cross(axis("I", eq[2]), axis("J", eq[1])))
                torque = plus(torque, turn, L)
        if jflag:
            d = [self.measure(tape, n, [jo.i, jo.j, rm]) for n in ("DX", "DY", "DZ")]
            minus = tape.const(-1.0)
            torque = [tape.op(mul, minus, x) for x in plus(torque, cross(d, force))]
            force = [tape.op(mul, minus, x) for x in force]
        return force, torque

    # element tapes -------------------------------------------------------------------------
    def motion(self, tape, mo):
        """Slots (g, g', expr, kind) of a Motion_Marker: g the driven measure (less expr for a
        displacement motion), g' its total time derivative, which the kernel constrains."""
        phi = self.lower_for_rate(tape, motions.measure(mo))
        f = self.lower(tape, mo.expr)
        g = tape.op(lib.PS_OP_SUB, phi, f) if mo.val_type == "D" else phi
        if mo.val_type == "D" and mo.direction.startswith("B"):
            # an angle's error wrapped to (-pi, pi]: the measured angle (B1, B3, a joint's AZ)
            # jumps by 2 pi where a driven rotation passes pi, atan2(sin e, cos e) does not
            g = tape.op(lib.PS_OP_ATAN2, tape.op(lib.PS_OP_SIN, g), tape.op(lib.PS_OP_COS, g))
        gd = tape.emit(lib.PS_OP_GDOT, g)
        tape.has_gdot = True
        return g, gd, f, {"D": lib.PS_MOTION_D, "V": lib.PS_MOTION_V, "A": lib.PS_MOTION_A}[
            mo.val_type]

    def element(self, kind, eid, tape, *ints):
        """Add an element of `kind` to the table: its tape and its ints in the catalogue's
        layout."""
        if len(ints) != len(catalogue.ELEMENT_OF_KIND[kind].ints):
            raise AssertionError(f"{kind} {eid}: {len(ints)} ints for its layout")
        self.elements.append((kind, eid, tape, tuple(int(v) for v in ints)))

    def joint(self, ti, tape, jo):
        """A joint's equations g in one tape, each with g' (its rate, which the kernel holds
        with the reaction lam; g itself with mu): one table row per equation."""
        rows = {eq: k for k, (jid, eq) in enumerate(self.layout.joint_rows) if jid == jo.id}
        base = len(self.layout.motion_ids)
        self.marker(tape, jo.i)           # I's body first, then J's
        self.marker(tape, jo.j)
        for n, eq in enumerate(catalogue.JOINT_EQUATIONS[jo.type]):
            if n not in rows:
                continue
            k = rows[n]
            g = self.lower_for_rate(tape, joints.equation_tree(jo, eq))
            gd = tape.emit(lib.PS_OP_GDOT, g)
            tape.has_gdot = True
            self.element("joint", jo.id, ti, g, gd, self.layout.lam[base + k],
                         self.layout.mu[base + k])

    def joint_initial(self):
        """The joints' initial conditions (Joint.ic), each a tape of its coordinate (DZ(I, J,
        J) or AZ(I, J)) and of its rate (VZ(I, J, J, J) or WZ(I, J, J)), which only the
        initial-conditions analysis reads (pysolver.build.icjoint): [(joint id, "T" or "R",
        displacement, velocity, (tape, slot) of the coordinate, (tape, slot) of its rate,
        the state indices of the two bodies' velocities)]."""
        out, lay = [], self.layout
        for jid in sorted(self.model.joints):
            jo = self.model.joints[jid]
            bodies = [lay.index.get(self.model.markers[m].body) for m in (jo.i, jo.j)]
            entries = [s for bi in bodies if bi is not None
                       for s in range(lay.uadr[bi], lay.uadr[bi] + lay.sizes[bi][1])]
            for coord, disp, vel in jo.ic:
                ti, tape = self.new_tape()
                turn = coord == "R"
                g = self.lower(tape, ex.call("AZ", jo.i, jo.j) if turn else
                               ex.call("DZ", jo.i, jo.j, jo.j))
                rate = self.lower(tape, ex.call("WZ", jo.i, jo.j, jo.j) if turn else
                                  ex.call("VZ", jo.i, jo.j, jo.j, jo.j))
                out.append((jid, coord, disp, vel, (ti, g), (ti, rate), entries))
        return out

    def held_expression(self, ti, tape, kind, gc):
        """A Constraint_General's (or a coupler's) expression g(q, t) as one constraint
        equation (held like a joint's: its rate with lam, itself with mu), if it is not
        redundant."""
        lay = self.layout
        if (kind, gc.id, 0) not in lay.constraint_rows:
            return
        k = len(lay.motion_ids) + lay.constraint_rows.index((kind, gc.id, 0))
        if lay.mu[k] < 0:                 # g(q, u, t) = 0: velocities read, held as it is
            tape.second_in_u = True
            g = self.lower(tape, gc.expr)
            self.element(kind, gc.id, ti, g, g, lay.lam[k], -1)
            return
        g = self.lower_for_rate(tape, gc.expr)
        gd = tape.emit(lib.PS_OP_GDOT, g)
        tape.has_gdot = True
        self.element(kind, gc.id, ti, g, gd, lay.lam[k], lay.mu[k])

    def turned_angle(self, key):
        """The measured angle (in (-pi, pi]) that tracked angle `key` follows."""
        kind, eid, k = key
        if kind == "unwrap":                      # AX(i, j) of an expression: its turns
            return ex.call(*eid)
        if kind == "sforce":
            sf = self.model.sforces[eid]
            return ex.call("AZ", sf.i, sf.j)
        if kind == "joint":
            jo = self.model.joints[eid]
            return joints.lead_angle(jo.i, jo.j, catalogue.JOINT_EQUATIONS[jo.type][0])
        jo = self.model.joints[self.model.couplers[eid].joints[k]]
        return ex.call("AZ", jo.i, jo.j)

    def new_tape(self):
        t = _Tape(self)
        self.tapes.append(t)
        return len(self.tapes) - 1, t

    def compile(self):
        model = self.model
        #: the element table, in the kernel's order: (kind, id, tape, ints)
        self.elements = []
        for pid in sorted(model.penalties):
            ti, t = self.new_tape()
            self.element("penalty", pid, ti, *self.penalty_force(t, pid))
        for sid in sorted(model.sforces):
            sf = model.sforces[sid]
            ti, t = self.new_tape()
            self.marker(t, sf.i)          # I's body first, then J's: the kernel relies on it
            self.marker(t, sf.j)
            f = self.lower(t, sf.expr)
            mode = int(sf.torque) | (2 if sf.action_only else 0)   # csrc/elements/sforce.c
            self.element("sforce", sid, ti, f, mode, self.midx[sf.i], self.midx[sf.j])
        for vid in sorted(model.vforces):
            vf = model.vforces[vid]
            ti, t = self.new_tape()
            mi, si = self.marker(t, vf.i)
            _, sj = self.marker(t, vf.j)
            mr, sr = self.marker(t, vf.ref)
            self.element("vforce", vid, ti, *[self.lower(t, e) for e in vf.exprs], mi, si, sj,
                         mr, sr)
        self.motion_slots = {}            # motion id -> (tape, slot) of g (its measure for V, A)
        for k, mid in enumerate(self.layout.motion_ids):
            ti, t = self.new_tape()
            g, gd, f, kind = self.motion(t, model.motions[mid])
            self.motion_slots[mid] = (ti, g)
            self.element("motion", mid, ti, f, gd, g, kind, self.layout.lam[k],
                         self.layout.rate[k], self.layout.mu[k])
        for jid in sorted(model.joints):
            ti, t = self.new_tape()
            self.joint(ti, t, model.joints[jid])
        self.joint_ic = self.joint_initial()
        for kind, table in (("gcon", model.gcons), ("coupler", model.couplers)):
            for cid in sorted(table):
                ti, t = self.new_tape()
                self.held_expression(ti, t, kind, table[cid])
        for key, state in self.layout.turns.items():
            ti, t = self.new_tape()
            self.element("turn", key[1], ti, self.turn_error(t, self.turned_angle(key),
                                                             key)[1], state)
        # forces that read SENVAL need a restart with consistent yp when a value is stored
        self.forces_use_senval = any(self.tapes[t].uses_senval
                                     for kind, _, t, _ in self.elements if kind != "motion")
        self.sensor = []
        cmp = {"GE": lib.PS_CMP_GE, "LT": lib.PS_CMP_LT, "EQ": lib.PS_CMP_EQ}
        for sid in sorted(model.sensors):
            se = model.sensors[sid]
            ti, t = self.new_tape()
            self.sensor.append((ti, self.lower(t, se.expr), cmp[se.compare], se.value,
                                se.error_tol))
        self.evaluate = []
        for eid in sorted(model.evaluates):
            ti, t = self.new_tape()
            self.evaluate.append((ti, self.lower(t, model.evaluates[eid].expr)))
        # LoadControl targets, evaluated by the controller at its updates
        self.ctrl = []
        for lid in sorted(model.controls):
            ti, t = self.new_tape()
            self.ctrl.append((ti, self.lower(t, model.controls[lid].load_expr)))
        self.out = []
        self.channels = []
        for rid in sorted(model.requests):
            req = model.requests[rid]
            ti, t = self.new_tape()
            for k, e in enumerate(req.exprs):
                self.out.append((ti, self.lower(t, e)) if e is not None else (-1, 0))
                self.channels.append((rid, k))
        # per joint, channels (-id, 0..8): its force and torque on I's body at I and
        # d = oI - oJ, global (Result.joint)
        for jid in sorted(model.joints):
            ti, t = self.new_tape()
            force, torque = self.joint_reaction(t, jid, 0, 0)
            jo = model.joints[jid]
            d = [self.measure(t, n, [jo.i, jo.j, 0]) for n in ("DX", "DY", "DZ")]
            for k, slot in enumerate(force + torque + d):
                self.out.append((ti, slot))
                self.channels.append((-jid, k))
        return self.arrays()

    def arrays(self):
        """Return a dict of numpy arrays and sizes for the psModel fields."""
        lay, model = self.layout, self.model
        i32 = lambda v: np.ascontiguousarray(v, dtype=np.int32)
        f64 = lambda v: np.ascontiguousarray(v, dtype=np.float64)
        code, tcode, tlen, tbadr, tnb, tbody, tnbody, tord = [], [], [], [], [], [], [], []
        tnh, tnst = [], []
        bkind, bidx, tb_body, tb_q, tb_u, tb_a, tb_w = [], [], [], [], [], [], []
        for t in self.tapes:
            tcode.append(len(code))
            tlen.append(len(t.code))
            code.extend(t.code)
            tbadr.append(len(bkind))
            tbody.append(len(tb_body))
            tnbody.append(len(t.bodies))
            tord.append(int(t.has_gdot))
            # basis: positions of every body, then time, then velocities, then u'
            slots = [(lay.bodies[bi], bi, need_u, need_a) for bi, need_u, need_a, _ in t.bodies]
            tb_w.extend(int(need_w) for *_, need_w in t.bodies)
            sizes = [lay.sizes[bi] for _, bi, *_ in slots]
            n = 0
            for (_, bi, _, _), (nq, _) in zip(slots, sizes):
                tb_body.append(bi)
                tb_q.append(n)
                bkind += [lib.PS_BASIS_Y] * nq
                bidx += list(range(lay.qadr[bi], lay.qadr[bi] + nq))
                n += nq
            # velocities u (entries of y), then accelerations u' (entries of yp); a tape of a
            # velocity-level constraint puts u before time, among the directions with second
            # derivatives (time stays the last of them: csrc/tape.c reads it there)
            stages = [(2, lib.PS_BASIS_Y, tb_u), "T", (3, lib.PS_BASIS_YP, tb_a)]
            if not t.second_in_u:
                stages = ["T"] + stages[:1] + stages[2:]
            for stage in stages:
                if stage == "T":
                    bkind.append(lib.PS_BASIS_T)
                    bidx.append(0)
                    n += 1
                    tnh.append(n)
                    continue
                flag, kind, where = stage
                for slot, (_, nu) in zip(slots, sizes):
                    bi, needed = slot[1], slot[flag]
                    where.append(n if needed else -1)
                    if needed:
                        bkind += [kind] * nu
                        bidx += list(range(lay.uadr[bi], lay.uadr[bi] + nu))
                        n += nu
            # extra state entries (motion reactions) read by PS_OP_STATE
            bkind += [lib.PS_BASIS_Y] * len(t.states)
            bidx += list(t.states)
            n += len(t.states)
            tnst.append(len(t.states))
            tnb.append(n)
        stride = max((1 + n + h * (h + 1) // 2 for n, h in zip(tnb, tnh)), default=2)
        # markers in their body's frame (ground markers: global)
        mbody, mpos, mrot = [], [], []
        for mid in self.markers:
            m = model.markers[mid]
            b = model.bodies[m.body]
            if b.kind == "ground":
                mbody.append(-1)
                mpos.append(m.pos)
                mrot.append(m.rot)
            else:
                mbody.append(lay.index[b.id])
                mpos.append(b.rot.T @ (m.pos - b.pos))
                mrot.append(b.rot.T @ m.rot)
        # a planar body's inertia in global axes at rz = 0 (its zz is Izz), and its plane
        inertia = [planar_global_inertia(b) if b.id in lay.planar else
                   b.inertia if b.kind == "rigid" else np.zeros((3, 3)) for b in lay.bodies]
        plane = [planar_plane_rows(b) if b.id in lay.planar else [0.0] * 10
                 for b in lay.bodies]
        return dict(
            ny=lay.ny, nbody=len(lay.bodies), nmarker=len(self.markers), ntape=len(self.tapes),
            nout=len(self.out),
            hd_stride=stride,
            max_slots=max(tlen, default=1) or 1, max_bslots=max(tnbody, default=1) or 1,
            gravity=list(model.gravity), force_scale=model.force_scale,
            body_type=i32([lib.PS_BODY_POINT if b.kind == "point" else
                           lib.PS_BODY_PLANAR if b.id in lay.planar else lib.PS_BODY_RIGID
                           for b in lay.bodies]),
            body_plane=f64(np.array(plane).reshape(-1)),
            body_qadr=i32(lay.qadr), body_uadr=i32(lay.uadr),
            body_mass=f64([b.mass for b in lay.bodies]),
            body_inertia=f64(np.array(inertia).reshape(-1)),
            marker_body=i32(mbody), marker_pos=f64(np.array(mpos).reshape(-1)),
            marker_rot=f64(np.array(mrot).reshape(-1)),
            tape_code_adr=i32(tcode), tape_len=i32(tlen), tape_basis_adr=i32(tbadr),
            tape_nbasis=i32(tnb), tape_nh=i32(tnh), tape_body_adr=i32(tbody),
            tape_nbody=i32(tnbody),
            tape_order=i32(tord), tape_nstate=i32(tnst),
            code=i32(np.array(code, dtype=np.int32).reshape(-1)),
            consts=f64(self.consts), basis_kind=i32(bkind), basis_idx=i32(bidx),
            tbody_body=i32(tb_body), tbody_q=i32(tb_q), tbody_u=i32(tb_u), tbody_a=i32(tb_a),
            tbody_w=i32(tb_w),
            nel=len(self.elements),
            el_kind=i32([getattr(lib, catalogue.ELEMENT_OF_KIND[k].c) for k, *_ in self.elements]),
            el_tape=i32([t for _, _, t, _ in self.elements]),
            el_adr=i32(np.cumsum([0] + [len(v) for *_, v in self.elements])[:-1]),
            el_int=i32([i for *_, v in self.elements for i in v]),
            # 1 a reaction, 2 a tracked angle (algebraic too, but a position to keep)
            state_alg=i32(np.isin(np.arange(lay.ny), lay.algebraic)
                          + np.isin(np.arange(lay.ny), list(lay.turns.values()))),
            compliance=f64(np.zeros(lay.ny)),     # set by the Kernel (compliance.py)
            out_tape=i32([o[0] for o in self.out]), out_slot=i32([o[1] for o in self.out]),
            nsensor=len(self.sensor), sensor_tape=i32([x[0] for x in self.sensor]),
            sensor_slot=i32([x[1] for x in self.sensor]),
            sensor_compare=i32([x[2] for x in self.sensor]),
            sensor_value=f64([x[3] for x in self.sensor]),
            sensor_tol=f64([x[4] for x in self.sensor]),
            **self.user_arrays(i32, f64),
        )

    def user_arrays(self, i32, f64):
        """psModel fields of the user subroutines the kernel calls."""
        routines = self.model.user_routines
        par_adr, key_adr, par, keys = [], [], [], []
        for r in routines:
            par_adr.append(len(par))
            par.extend(r.par)
            key_adr.append(len(keys))
            keys.extend(r.keys)
        return dict(
            nuser=len(routines), nusercache=len(self._user_cache), user_fn=[r.fn for r in routines],
            user_form=i32([r.form for r in routines]), user_id=i32([r.id for r in routines]),
            user_par_adr=i32(par_adr), user_npar=i32([len(r.par) for r in routines]),
            user_par=f64(par), user_key_adr=i32(key_adr),
            user_nkey=i32([len(r.keys) for r in routines]),
            user_timeless=i32([r.timeless for r in routines]),
            user_python=i32([r.python for r in routines]),
            user_name=[r.name for r in routines],
            user_key_fn=i32([lib.ps_user_fn_code(k.split("(")[0].encode()) for k in keys]),
            user_key_n=i32([len(_key_ids(k)) for k in keys]),
            user_key_ids=i32([(_key_ids(k) + [0] * 4)[:4] for k in keys]).reshape(-1),
            user_in=i32(self.user_in))
