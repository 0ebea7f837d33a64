"""Generated C for large scenes: one C function per distinct shape of body or element, looped
over that shape's instances through an index table.

Straight-line C (:mod:`.emit`) costs compile time in proportion to the scene, and a chain of
5000 links is 5000 copies of one link. Here each body and each element is renumbered from zero
(its bodies, states, markers, constants and sensor values, in order of first use) into a scene
of its own. Elements whose renumbered scenes are equal share a template, built and
differentiated once (:class:`~.scene.Scene`, :class:`~.assemble.Assembly`) and run in a loop
over a table of each instance's global indices: its states (rows and columns), bodies, markers,
constants, sensor values and the positions of its iteration-matrix entries, which it adds
into. Every constant is read at run time (``m->consts[I[k]]``), and so are the markers'
orientations in a template whose instances differ in them, so elements that differ only in
their numbers share a template. Sensor expressions and request channels are templates too, one
part per tape they read, writing the sensors or channels in their table.
"""
import numpy as np

from ..bindings import lib
from .assemble import KINDS, Assembly
from .emit import STRIDE, Emitter
from .scene import OP, Scene
from .sym import Unsupported

_W = lib.PS_INSTR_WIDTH

# operands of a tape instruction that name markers, constants, states and sensor values
_MARKERS = {OP["MEASURE"]: (2, 3, 4, 5), OP["AXDOT"]: (1, 3)}
_CONSTS = {OP["CONST"]: (1,), OP["STEPC"]: (2, 3, 4, 5)}

#: The arrays of an element-free scene, to which a part adds its own.
_NO_ELEMENTS = {"nel": 0, "el_kind": [], "el_tape": [], "el_adr": [], "el_int": [],
                "nsensor": 0, "nout": 0,
                "sensor_tape": [], "sensor_slot": [], "out_tape": [], "out_slot": []}


class Part:
    """One body or element of a scene renumbered from zero.

    Attributes
    ----------
    arrays : dict
        Its scene of its own, in the arrays :class:`~.scene.Scene` reads.
    tables : list of list of int
        The global index of each of its states, bodies, markers, constants and sensor values.
    """

    def __init__(self, a):
        self.a = a
        self.tables = [[], [], [], [], []]
        self._ids = {}, {}
        self.qadr, self.uadr, self.mbody, self.code, self.ntbody = [], [], [], [], 0
        self.user_in = []       # the input slots of its user subroutine calls
        self.extra = []         # sensor or channel indices of a sensors' or requests' part

    def state(self, i):
        """The renumbered index of global state i (negative: none)."""
        if i < 0:
            return i
        got = self._ids[0].get(i)
        if got is None:
            got = self._ids[0][i] = len(self.tables[0])
            self.tables[0].append(i)
        return got

    def body(self, b):
        """The renumbered index of global body b, its coordinates added to the states."""
        if b < 0:
            return -1
        got = self._ids[1].get(b)
        if got is None:
            a = self.a
            got = self._ids[1][b] = len(self.tables[1])
            self.tables[1].append(b)
            nq, nu = (7, 6) if a["body_type"][b] == lib.PS_BODY_RIGID else (3, 3)  # planar too
            for adr, n, out in ((a["body_qadr"][b], nq, self.qadr), (a["body_uadr"][b], nu,
                                                                     self.uadr)):
                first = len(self.tables[0])
                if any(self.state(int(adr) + i) != first + i for i in range(n)):
                    raise Unsupported("a state entry of a body read before the body")
                out.append(first)
        return got

    def marker(self, mk):
        """A renumbered marker (one per use: equal uses need not be the same marker)."""
        if mk < 0:
            return -1
        self.tables[2].append(mk)
        self.mbody.append(self.body(int(self.a["marker_body"][mk])))
        return len(self.tables[2]) - 1

    def const(self, k):
        self.tables[3].append(k)
        return len(self.tables[3]) - 1

    def tape(self, t):
        """Renumber tape t, its bodies first (they become bodies 0, 1, ...)."""
        a = self.a
        adr, n = int(a["tape_body_adr"][t]), int(a["tape_nbody"][t])
        for b in a["tbody_body"][adr:adr + n]:
            self.body(int(b))
        if self.tables[1] != [int(b) for b in a["tbody_body"][adr:adr + n]]:
            raise AssertionError("a tape renumbered after another")
        self.ntbody = n
        start, length = int(a["tape_code_adr"][t]), int(a["tape_len"][t])
        code = a["code"][start * _W:(start + length) * _W].tolist()
        for i in range(0, len(code), _W):
            op = code[i]
            for j in _MARKERS.get(op, ()):
                code[i + j] = self.marker(code[i + j])
            for j in _CONSTS.get(op, ()):
                code[i + j] = self.const(code[i + j])
            if op == OP["STATE"]:
                code[i + 1] = self.state(code[i + 1])
            elif op == OP["SENVAL"]:
                self.tables[4].append(code[i + 1])
                code[i + 1] = len(self.tables[4]) - 1
            elif op == OP["USER"]:
                # its inputs' slots move into the part; routine and cache entry stay global,
                # so a part that calls a routine is a template of its own
                adr, nin = code[i + 2], code[i + 3]
                code[i + 2] = len(self.user_in)
                self.user_in.extend(int(v) for v in a["user_in"][adr:adr + nin])
        self.code = code
        return 0

    def finish(self, **element):
        """Set :attr:`arrays` to the part's own scene with `element` in it; return the key
        that parts of one template share (all but the markers' rotations, :attr:`rot`)."""
        a = self.a
        rot = a["marker_rot"]
        self.element = bool(element)
        self.arrays = m = dict(_NO_ELEMENTS)
        m.update(
            nuser=0, user_in=self.user_in, ny=len(self.tables[0]), force_scale=a["force_scale"],
            nbody=len(self.tables[1]), body_qadr=self.qadr, body_uadr=self.uadr,
            body_type=[int(a["body_type"][b]) for b in self.tables[1]],
            marker_body=self.mbody,
            marker_rot=[v for mk in self.tables[2] for v in rot[9 * mk:9 * mk + 9].tolist()],
            consts=[0.0] * len(self.tables[3]), code=self.code, tape_code_adr=[0],
            tape_len=[len(self.code) // _W], tape_body_adr=[0], tape_nbody=[self.ntbody],
            tbody_body=list(range(self.ntbody)))
        m.update(element)
        self.rot = tuple(m["marker_rot"])
        return repr(sorted(item for item in m.items() if item[0] != "marker_rot"))

    def row(self):
        """The part's index table row: its global states, bodies, markers, constants, sensor
        values, and sensors or channels."""
        return [i for table in self.tables for i in table] + self.extra


def parts(a):
    """Every body and element of the scene with arrays `a`, as :class:`Part` objects."""
    out = []
    for b in range(int(a["nbody"])):
        p = Part(a)
        p.body(b)
        out.append((p, p.finish()))
    for e in range(int(a["nel"])):
        kind = KINDS[int(a["el_kind"][e])]
        adr = int(a["el_adr"][e])
        p = Part(a)
        tape = p.tape(int(a["el_tape"][e]))
        # markers and states renumbered into the part's own; slots, flags and body slots kept
        renumber = {"marker": p.marker, "state": p.state}
        ints = [renumber.get(field.split(":")[1], int)(int(v))
                for field, v in zip(kind.ints, a["el_int"][adr:adr + len(kind.ints)])]
        out.append((p, p.finish(nel=1, el_kind=[int(a["el_kind"][e])], el_tape=[tape],
                                el_adr=[0], el_int=ints)))
    return out


class Template:
    """The generated code of one shape of part, and the index table of its instances."""

    def __init__(self, members, limit):
        first = members[0]
        # markers' rotations are folded in when every instance has the same, else read
        same = all(p.rot == first.rot for p in members)
        self.scene = s = Scene(first.arrays, range(len(first.tables[3])), limit,
                               rotations_at_run_time=not same)
        self.asm = Assembly(s, bodies=not first.element, elements=first.element)
        self.widths = [len(t) for t in first.tables]
        self.rows = [p.row() for p in members]

    def leaf(self, op, arg):
        """C text of a run-time leaf, through the instance's index table I."""
        nq, nb, nm, nc, _ = self.widths
        if op in ("y", "yp"):
            return f"{op}[I[{arg}]]"
        if op == "sv":
            return f"d->senval[I[{nq + nb + nm + nc + arg}]]"
        array, obj, comp = arg
        if array == "gravity":
            return f"m->gravity[{comp}]"
        if array == "compliance":                      # per state, like y
            return f"m->compliance[I[{obj}]]"
        base = {"body_mass": nq, "body_inertia": nq, "body_plane": nq, "marker_pos": nq + nb,
                "marker_rot": nq + nb, "consts": nq + nb + nm}[array] + obj
        stride = STRIDE.get(array, 1)
        index = f"I[{base}]" if stride == 1 else f"{stride} * I[{base}] + {comp}"
        return f"m->{array}[{index}]"


def channels(a):
    """Parts for the sensor expressions and request channels, one per tape they read, with
    ``extra`` the global sensor or channel index of each: (family, part, key) triples."""
    out = []
    for family, n, tapes, slots in (("o", a["nout"], a["out_tape"], a["out_slot"]),
                                    ("s", a["nsensor"], a["sensor_tape"], a["sensor_slot"])):
        by_tape = {}
        for k in range(int(n)):
            if tapes[k] >= 0:                # a NULL channel reads no tape
                by_tape.setdefault(int(tapes[k]), []).append((k, int(slots[k])))
        for t, chans in by_tape.items():
            p = Part(a)
            p.tape(t)
            p.extra = [k for k, _ in chans]
            fields = ({"nout": len(chans), "out_tape": [0] * len(chans),
                       "out_slot": [sl for _, sl in chans]} if family == "o" else
                      {"nsensor": len(chans), "sensor_tape": [0] * len(chans),
                       "sensor_slot": [sl for _, sl in chans]})
            out.append((family, p, family + p.finish(**fields)))
    return out


def generate(kernel, limit=None):
    """The looped C source of a compiled kernel (raises Unsupported past `limit` nodes)."""
    a = kernel.arrays
    # parts by family (r the residual and iteration matrix, o outputs, s sensors) and key
    groups = {"r": {}, "o": {}, "s": {}}
    for family, part, key in [("r", p, k) for p, k in parts(a)] + channels(a):
        groups[family].setdefault(key, []).append(part)
    families, used = {}, 0
    for family, by_key in groups.items():
        families[family] = {}
        for key, members in by_key.items():
            tpl = Template(members, None if limit is None else limit - used)
            families[family][key] = tpl
            used += len(tpl.scene.g.op)
    ny = int(a["ny"])
    res = list(families["r"].values())
    trip, positions = _pattern(res, ny)
    em = Emitter()
    for k, (tpl, pos) in enumerate(zip(res, positions)):
        g, base = tpl.scene.g, sum(tpl.widths)
        em.function(g, f"psg_r{k}", [(f"out[I[{r}]]", n) for r, n in enumerate(tpl.asm.res)
                                     if n != g.zero], tpl.leaf, indexed=True, assign="+=")
        em.function(g, f"psg_j{k}", [(f"out[I[{base + i}]]", n)
                                     for i, (_, _, n) in enumerate(tpl.asm.trip)],
                    tpl.leaf, indexed=True, assign="+=")
        _table(em, f"psg_ir{k}", np.hstack([np.array(tpl.rows, dtype=np.int64), pos]))
    for family, attr in (("o", "outputs"), ("s", "sensors")):
        for k, tpl in enumerate(families[family].values()):
            base = sum(tpl.widths)
            em.function(tpl.scene.g, f"psg_{family}{k}",
                        [(f"out[I[{base + i}]]", n) for i, n in enumerate(getattr(tpl.asm, attr))],
                        tpl.leaf, indexed=True)
            _table(em, f"psg_i{family}{k}", np.array(tpl.rows, dtype=np.int64))
    for name, family, fn, fill in (("psg_residual", "r", "r", f"{ny}, 0.0"),
                                   ("psg_jacobian", "r", "j", f"{len(trip)}, 0.0"),
                                   ("psg_outputs", "o", "o", f"{int(a['nout'])}, NAN"),
                                   ("psg_sensors", "s", "s", "0, 0.0")):
        size, value = fill.split(", ")
        loops = "\n".join(f"  for (int k = 0; k < {len(tpl.rows)}; k++) "
                          f"psg_{fn}{i}(m, d, t, y, yp, cj, out, psg_i{family}{i}[k]);"
                          for i, tpl in enumerate(families[family].values()))
        em.parts.append(f"static void {name}(const psModel* m, psData* d, double t, "
                        f"const double* y, const double* yp, double cj, double* out) {{\n"
                        f"  (void)m; (void)d; (void)t; (void)y; (void)yp; (void)cj;\n"
                        f"  for (int i = 0; i < {size}; i++) out[i] = {value};\n{loops}\n}}\n")
    em.table(ny, trip, int(a["nsensor"]), int(a["nout"]))
    return em.source()


def _table(em, name, table):
    """Emit an (instances x entries) index table as a static C array."""
    rows = ",\n".join("{" + ", ".join(map(str, row)) + "}" for row in table.tolist())
    em.parts.append(f"static const int {name}[{table.shape[0]}][{table.shape[1]}] = "
                    f"{{\n{rows}}};\n")


def _pattern(templates, ny):
    """The scene's iteration-matrix pattern as sorted (row, col) pairs (column-major), and for
    each template an (instances x entries) array of the positions its entries add into."""
    keys = []
    for tpl in templates:
        q = np.array(tpl.rows, dtype=np.int64)[:, :tpl.widths[0]]
        r = np.array([e[0] for e in tpl.asm.trip], dtype=np.int64)
        c = np.array([e[1] for e in tpl.asm.trip], dtype=np.int64)
        keys.append(q[:, c] * ny + q[:, r])
    every = np.unique(np.concatenate([k.ravel() for k in keys])) if keys else np.zeros(0, int)
    trip = [(int(k % ny), int(k // ny)) for k in every]
    return trip, [np.searchsorted(every, k) for k in keys]
