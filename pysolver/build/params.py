"""Numbers of a compiled model that the cases of a sweep change without recompiling.

A case is a dict of paths such as ``"Force_Penalty/10/penalty"`` or ``"Body_Point/2/v_ic_x"``
to numbers. Each path names a number the kernel reads at run time, never a constant baked into
its instructions: penalty coefficients and named numbers (a Reference_Variable that is a
number, read with VARVAL) have constant slots of their own (the compiler's parameters); masses,
inertias, marker positions, gravity and sensor thresholds are entries of the kernel's arrays;
initial velocities and positions make the initial state; Param_Transient and Param_Static
settings are run options. :meth:`Parameters.apply` puts the deck's values back first, so cases
never leak into each other. Paths are case-insensitive in the element and attribute names (a
case giving one twice is a DeckError).

Each path is the deck's own number in the frame the deck gives it in, so a case is the deck
edited by hand: a marker's ``pos_*`` in its rm_id's frame, an Adams QP in its part's
(:mod:`pysolver.build.places`), a body's ``v_ic_*`` along vm_id's axes and ``w_ic_*`` along
wm_id's (an Adams PART's WX.. along its CM marker's), else global.

A case's value obeys the rules the deck loader applies to the same attribute
(:func:`check_value`: the attribute's kind in :data:`pysolver.deck.schema.SCHEMA`, converted
by the loader's own :func:`pysolver.deck.schema.convert`, and for Param_Transient the option's
rule in :mod:`pysolver.options`): a penalty of 0 or -1e4, a smoothing factor of 0, ``True`` as
a number or a step count of 2.5 is the DeckError a deck with that value gets.
"""
import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from ..deck.bodies import centroidal, inertia_tensor, positive_definite, spin, velocity
from ..deck.schema import SCHEMA, Ctx, convert
from ..deck.validate import value_rule
from ..errors import DeckError
from ..options import DECK_NAMES, steps_problem
from .energy import energy_paths
from .places import Places
from .planar import global_inertia, plane_rows, why_not

_STATIC = ("max_ke_tol", "max_dq_tol", "max_num_iter", "max_imbalance", "max_error",
           "stability", "compliance_delta", "tlimit", "alimit")
_INERTIA = ("xx", "yy", "zz", "xy", "yz", "xz")


def _inertia_numbers(tensor):
    """A tensor's six deck numbers (xx, yy, zz, xy, yz, xz: products as positive integrals,
    the inverse of pysolver.deck.bodies.inertia_tensor)."""
    return [float(tensor[0, 0]), float(tensor[1, 1]), float(tensor[2, 2]),
            float(-tensor[0, 1]), float(-tensor[1, 2]), float(-tensor[0, 2])]


def _error(path, msg):
    parts = str(path).split("/")
    ident = int(parts[1]) if len(parts) == 3 and parts[1].isdigit() else None
    return DeckError(f"sweep parameter {path!r}: {msg}", element=parts[0] or None, id=ident,
                     attribute=parts[-1] if len(parts) > 1 else None)


#: The one attribute a case sets that has no attribute of its own in the deck: the number a
#: Reference_Variable's expression is (any finite real, as a constant of an expression).
_NOT_IN_SCHEMA = {("Reference_Variable", "value"): "float"}


_KINDS = {}                     # path -> (element, attribute, kind, its Ctx), as looked up

#: Numbers check_value takes as they are, and the elements whose values have rules beyond
#: their kind (deck.validate.value_rule).
_REALS = (int, float, np.floating, np.integer)
_RULED = frozenset({"Param_Transient", "Force_Gravity"})


def _assign(rec, **changes):
    """Change numbers of a record of a compiled model's own scene (its working copy: the loaded
    Model, whose records are read-only, never changes)."""
    for name, v in changes.items():
        object.__setattr__(rec, name, v)


def check_value(path, value):
    """`value` for the number `path` names (a canonical path of :meth:`Parameters.paths`),
    converted and checked by the rules the deck loader applies to that attribute; DeckError
    (its reason the loader's) when it breaks them."""
    got = _KINDS.get(path)
    if got is None:
        parts = path.split("/")
        tag, attr = parts[0], parts[-1]
        kind = _NOT_IN_SCHEMA.get((tag, attr)) or SCHEMA[tag][attr][0]
        got = _KINDS[path] = (tag, attr, kind, Ctx(None, tag, {}, None, {}))
    tag, attr, kind, ctx = got
    # a finite real for a real attribute, the usual case, without the loader's general path
    v = float(value) if kind in ("float", "pos", "nonneg") and isinstance(value, _REALS) \
        and not isinstance(value, bool) else None
    if v is None or not (math.isfinite(v) and (kind == "float" or (
            kind == "pos" and v > 0) or (kind == "nonneg" and v >= 0))):
        try:
            v = convert(ctx, attr, kind, value)
        except DeckError as err:
            raise _error(path, err.reason) from None
    problem = tag in _RULED and value_rule(tag, attr, v)   # the loader's rules beyond the kind
    if problem:
        raise _error(path, f"got {v:g}; {problem}")
    return v


class Parameters:
    """The changeable numbers of one compiled model.

    Parameters
    ----------
    model : pysolver.Model
    kernel : pysolver.build.kernel.Kernel
        Its compiled kernel (``model.compile().kernel``).
    """

    def __init__(self, model, kernel):
        self.model, self.kernel = model, kernel
        self._base = {}                 # path -> the deck's value, for the paths set so far
        self._deck = {}                 # path -> the deck's value, once read (they never change)
        self._places = None             # the markers' places (pysolver.build.places)
        self._rates = {}                # body id -> (v_ic, w_ic): the deck's, or a case's
        self._names = {}                # lower-case path -> canonical path
        self._dirty = set()             # bodies whose inertia about the cg must be remade
        # marker -> the body whose inertia about its cg follows it (an IM away from the cg)
        self._offset_markers = {mid: b.id for b in model.bodies.values()
                                if b.kind == "rigid" and b.im not in (None, b.cg)
                                for mid in (b.cg, b.im)}
        for path in self.paths():
            self._names[path.lower()] = path

    def paths(self):
        """Every path a case may set, sorted."""
        m = self.model
        # KE's copies of masses and inertias follow the bodies' own paths
        out = [p for p in self.kernel.params if not p.startswith("KE/")]
        for b in m.bodies.values():
            if b.kind == "ground":
                continue
            tag = "Body_Point" if b.kind == "point" else "Body_Rigid"
            out.append(f"{tag}/{b.id}/mass")
            out += [f"{tag}/{b.id}/v_ic_{c}" for c in "xyz"]
            if b.kind == "rigid":
                out += [f"{tag}/{b.id}/w_ic_{c}" for c in "xyz"]
                out += [f"{tag}/{b.id}/inertia_{k}" for k in _INERTIA]
        for mid, mk in m.markers.items():
            if m.bodies[mk.body].kind == "point" and m.bodies[mk.body].cg != mid:
                continue                  # a point body's only meaningful marker is its cg
            out += [f"Reference_Marker/{mid}/pos_{c}" for c in "xyz"]
        out += [f"Force_Gravity/grav_{c}" for c in "xyz"]
        for sid in m.sensors:
            out += [f"Sensor_Event/{sid}/value", f"Sensor_Event/{sid}/error_tol"]
        out += [f"Param_Transient/{k}" for k in DECK_NAMES]
        out += [f"Param_Static/{k}" for k in _STATIC]
        return sorted(out)

    def canonical(self, path):
        """The path as :meth:`paths` spells it; DeckError when the model has no such number."""
        got = self._names.get(str(path).lower())
        if got is None:
            raise _error(path, self._why_not(str(path)))
        return got

    def apply(self, case):
        """Put the deck's values back, then set those of `case` ({path: number}); return the
        run options the case sets (Param_Transient). A case that breaks a rule is a DeckError
        that leaves the deck's values in place; a `case` that is no dict a TypeError."""
        if not isinstance(case, Mapping):
            raise TypeError(f"params must be a dict {{path: number}}, got {case!r} "
                            f"({type(case).__name__})")
        self.reset()
        try:
            options = self._set_case(case)
            self._check_steps(options)
        except DeckError:
            self.reset()
            raise
        self._sync_places()
        self._sync_inertias(case)
        self._sync_planar(case)
        return options

    def _set_case(self, case):
        options, given = {}, {}
        for raw, value in case.items():
            path = self.canonical(raw)
            if path in given:
                raise _error(path, f"given twice in one case, as {given[path]!r} and {raw!r} "
                             "(paths are case-insensitive)")
            given[path] = raw
            v = check_value(path, value)
            kind, *key = path.split("/")
            if (kind == "Force_SpringDamper" and key[1] == "length" and v < 0
                    and self.model.springdampers[int(key[0])].type == "TRANSLATIONAL"):
                raise _error(path, f"got {v:g}; a free length is >= 0")
            if path.startswith("Param_Transient/"):
                options[path.split("/")[1]] = v
                continue
            if path not in self._base:
                base = self._deck.get(path)
                if base is None:
                    base = self._deck[path] = self._get(path)
                self._base[path] = base
            self._set(path, v)
        return options

    def _check_steps(self, options):
        """A DeckError when the case's h_min and h_max, with the deck's, cannot both hold."""
        if "h_min" in options or "h_max" in options:
            deck = self.model.transient
            problem = steps_problem(options.get("h_min", deck.h_min),
                                    options.get("h_max", deck.h_max))
            if problem:
                path = "Param_Transient/h_min" if "h_min" in options else \
                    "Param_Transient/h_max"
                raise _error(path, problem)

    def reset(self):
        """The deck's values everywhere."""
        if not self._base:
            return
        for path, v in self._base.items():
            self._set(path, v)
        self._base.clear()
        self._sync_places()
        if self._places is not None:
            self._places.forget()
        self._rates.clear()
        self._sync_inertias(None)
        self._sync_planar(None)

    def _sync_inertias(self, case):
        """The inertia about the centre of mass of each body whose mass, inertia or IM offset
        a case changed (a body's IM away from its cg: the parallel-axis term follows its mass
        and the two markers' places); one that is then not a body's inertia puts the deck's
        values back and is a DeckError."""
        k, m = self.kernel, self.model
        dirty, self._dirty = self._dirty, set()
        for bid in sorted(dirty):
            b = m.bodies[bid]
            offset = b.rot.T @ (m.markers[b.im].pos - b.pos) if b.im not in (None, b.cg) \
                else np.zeros(3)
            inertia = centroidal(b.inertia_im, b.im_rot, b.mass, offset)
            if case is not None and not positive_definite(inertia):
                self.reset()
                paths = ", ".join(f"{p}={v:g}" for p, v in case.items())
                raise DeckError(f"parameters {{{paths}}}: body {bid}'s inertia about its centre "
                                f"of mass (the inertia about IM marker {b.im} less the "
                                "parallel-axis term of its mass at the centre of mass) is not "
                                "positive definite",
                                element="Body_Rigid", id=bid)
            _assign(b, inertia=inertia)
            row = k.layout.index[b.id]
            k.arrays["body_inertia"][9 * row:9 * row + 9] = b.inertia.reshape(-1)
            self._sync_energy(b)

    def _sync_planar(self, case):
        """A planar kernel's body_plane and global inertias from the bodies' numbers; a case
        that takes the scene out of its plane (gravity, a velocity or an inertia product out
        of it, a joint marker off its height) puts the deck's values back and is a
        DeckError."""
        k = self.kernel
        planar = k.layout.planar
        if not planar:
            return
        why = None if case is None else why_not(self.model)
        if why is not None:
            self.reset()
            paths = ", ".join(f"{p}={v:g}" for p, v in case.items())
            raise DeckError(f"parameters {{{paths}}}: the model was compiled as a planar scene "
                            "(docs/numerics.md, \"Planar scenes\") and with these numbers "
                            f"{why}; to run them, set PYSOLVER_PLANAR=off and load the model "
                            "again (it then runs in 3-D)")
        for b in k.layout.bodies:
            if b.id in planar:
                row = k.layout.index[b.id]
                k.arrays["body_plane"][10 * row:10 * row + 10] = plane_rows(b)
                k.arrays["body_inertia"][9 * row:9 * row + 9] = global_inertia(b).reshape(-1)

    # one path -----------------------------------------------------------------------------
    def _get(self, path):
        kind, *key = path.split("/")
        m = self.model
        if path in self.kernel.params:
            return float(self.kernel.arrays["consts"][self.kernel.params[path]])
        if kind in ("Body_Point", "Body_Rigid"):
            b, attr = m.bodies[int(key[0])], key[1]
            if attr == "mass":
                return b.mass
            if attr.startswith("inertia_"):
                return _inertia_numbers(b.inertia_im)[_INERTIA.index(attr[8:])]
            rates = m.rates[b.id]
            return float((rates.w if attr.startswith("w_ic") else rates.v)["xyz".index(attr[-1])])
        if kind == "Reference_Marker":
            return float(m.placements[int(key[0])].local["xyz".index(key[1][-1])])
        if kind == "Force_Gravity":
            return float(m.gravity["xyz".index(key[0][-1])])
        if kind == "Sensor_Event":
            return float(getattr(m.sensors[int(key[0])], key[1]))
        if kind == "Param_Static":
            return float(getattr(m.static, key[0]))
        raise AssertionError(path)

    def _set(self, path, v):
        kind, *key = path.split("/")
        m, k = self.model, self.kernel
        if path in k.params:
            k.arrays["consts"][k.params[path]] = v
        elif kind in ("Body_Point", "Body_Rigid"):
            self._set_body(path, m.bodies[int(key[0])], key[1], v)
        elif kind == "Reference_Marker":
            if self._places is None:
                self._places = Places(m, k)
            self._places.set(int(key[0]), "xyz".index(key[1][-1]), v)
        elif kind == "Force_Gravity":
            m.gravity["xyz".index(key[0][-1])] = v
            k.m.gravity = k.arrays["gravity"] = list(m.gravity)   # the compliance reads both
        elif kind == "Sensor_Event":
            sid = int(key[0])
            _assign(m.sensors[sid], **{key[1]: v})
            row = sorted(m.sensors).index(sid)
            k.arrays["sensor_value" if key[1] == "value" else "sensor_tol"][row] = v
        elif kind == "Param_Static":
            m.static = dataclasses.replace(m.static, **{key[0]: type(getattr(m.static,
                                                                                key[0]))(v)})
        else:
            raise AssertionError(path)

    def _set_body(self, path, b, attr, v):
        k = self.kernel
        row = k.layout.index[b.id]
        if attr == "mass":
            _assign(b, mass=v)
            k.arrays["body_mass"][row] = v
            self._sync_energy(b)
            if b.kind == "rigid" and b.im not in (None, b.cg):
                self._dirty.add(b.id)
        elif attr.startswith("inertia_"):
            numbers = _inertia_numbers(b.inertia_im)
            numbers[_INERTIA.index(attr[8:])] = v
            raw = inertia_tensor(*numbers)
            if not positive_definite(raw):
                raise _error(path, "the inertia tensor must be positive definite")
            _assign(b, inertia_im=raw)
            self._dirty.add(b.id)
        else:
            # the deck's numbers, along its vm_id's / wm_id's axes when it gives one (an Adams
            # PART's WX.. along its CM marker's), placed again as the loader places them
            rates = self.model.rates[b.id]
            got = self._rates.get(b.id)
            if got is None:
                got = self._rates[b.id] = (rates.v.copy(), rates.w.copy())
            v_ic, w_ic = got
            markers = self.model.markers
            if attr.startswith("w_ic"):
                w_ic["xyz".index(attr[-1])] = v
                b.omega[:] = spin(w_ic, markers[b.cg], markers.get(rates.wm))
            else:
                v_ic["xyz".index(attr[-1])] = v
                b.vel[:] = velocity(v_ic, markers.get(rates.vm))

    def _sync_energy(self, b):
        """KE's constants of body b (pysolver.build.energy) after a change of its mass or
        inertia."""
        k = self.kernel
        values = [b.mass] + list(np.asarray(b.inertia).reshape(-1) if b.kind == "rigid"
                                 else [0.0] * 9)
        for path, v in zip(energy_paths(b), values):
            if path in k.params:
                k.arrays["consts"][k.params[path]] = v

    def _sync_places(self):
        """The markers whose numbers a case set, and those placed in their frames, placed as
        the deck places them (pysolver.build.places); a body whose IM offset they change gets
        its inertia about the cg again."""
        if self._places is not None:
            for mid in self._places.sync():
                if mid in self._offset_markers:
                    self._dirty.add(self._offset_markers[mid])

    def _why_not(self, path):
        parts = path.split("/")
        kinds = sorted({p.split("/")[0] for p in self._names.values()})
        if parts[0] not in kinds and parts[0].lower() not in {x.lower() for x in kinds}:
            return f"unknown element; sweeps change {', '.join(kinds)}"
        if parts[0].lower() == "force_penalty" and path.lower().endswith("/penalty1"):
            return ("the deck's penalty1 is 0, so the compiled model has no damping term to "
                    "change (a structural change: give the deck a nonzero penalty1)")
        near = [p for p in self._names.values() if p.lower().startswith(parts[0].lower() + "/")]
        if len(parts) == 3 and not any(p.lower().startswith("/".join(parts[:2]).lower() + "/")
                                       for p in near):
            ids = sorted({p.split("/")[1] for p in near if len(p.split("/")) == 3})
            return f"no {parts[0]} {parts[1]} in this model (its {parts[0]}s: {', '.join(ids)})"
        if len(parts) == 3 and parts[0].lower() in ("force_field", "force_beam") and \
                parts[2].lower() in SCHEMA[parts[0].title()]:
            return (f"the deck's {parts[2]} is 0, so the compiled model has no term of it to "
                    f"change (a structural change: give the deck a nonzero {parts[2]})")
        return ("no such number in this model (structural attributes such as ids, types and "
                f"flags cannot change); this element's: {', '.join(near[:12])}")
