"""The validated scene: the :class:`Model` that holds the records of its elements
(:mod:`pysolver.records`, re-exported here), read-only once loaded.
The deck readers (:mod:`pysolver.deck`) build it, :mod:`pysolver.build` lays it out for the
C kernel, :mod:`pysolver.solve` runs it; :meth:`Model.run` imports those stages when called.
"""
from __future__ import annotations

import os
from typing import TYPE_CHECKING

import numpy as np

from . import catalogue, imports
from .errors import DeckError
from .options import SPARSE_THRESHOLD, Options, resolve_kernel
from .records import (  # noqa: F401 - the records are the model's vocabulary
    READ_ONLY,
    UNIT_DEFAULTS,
    Body,
    Evaluate,
    Graphic,
    LoadControl,
    Marker,
    Motion,
    Penalty,
    Placement,
    Rates,
    Request,
    ScalarForce,
    Sensor,
    Simulate,
    Source,
    Spline,
    Static,
    UserSub,
    Variable,
    VectorForce,
    _copy,
    _read_only,
    record,
)

if TYPE_CHECKING:               # for annotations only: results come later in the flow
    from .results import Result


class Model:
    """A validated scene, ready to run.

    Build one with :func:`pysolver.load`. Attributes hold the elements by id; ``commands``
    lists the Simulate commands in deck order.
    """

    def __init__(self, source):
        self.source = source
        self.units = dict(UNIT_DEFAULTS)
        self.force_scale = 1.0
        self.gravity = np.zeros(3)
        # the elements by id, one table per kind (catalogue.ELEMENTS: markers, bodies,
        # penalties, sforces, vforces, motions, controls, variables, requests, sensors, ...)
        for element in catalogue.ELEMENTS:
            setattr(self, element.table, {})
        self.transient = Options()      # Param_Transient
        self.output_settings = {}       # ResOutput, H3DOutput: kept as written, not used
        self.static = Static()
        self.commands = []
        # the deck's own numbers of marker places and initial rates, in the frames it gives
        # them in (the paths of run(params=...) and sweeps mean them): marker id -> Placement,
        # body id -> Rates
        self.placements = {}
        self.rates = {}
        self.default_command = False    # no Simulate: the default transient (validate)
        self.has_units = False
        self._compiled = {}       # CompiledModel by kind of kernel (compile)
        self.usersub_paths = {}   # element -> how its user subroutine runs (filled when compiled)
        self.user_routines = []   # routines the kernel calls (pysolver.build.usercalls)
        self._scripts = {}        # user subroutine scripts run so far: path -> namespace
        self._where = {}          # (kind, id) -> location of the element, for errors

    def __setattr__(self, name, value):
        if self.__dict__.get("_frozen") and not name.startswith("_"):
            _read_only(self, name)
        object.__setattr__(self, name, value)

    def _freeze(self):
        """End of loading: from here on the model reads only (READ_ONLY says what to do)."""
        self.gravity.flags.writeable = False
        for b in self.bodies.values():
            for arr in (b.inertia, b.pos, b.rot, b.vel, b.omega, b.im_rot, b.inertia_im):
                if isinstance(arr, np.ndarray):
                    arr.flags.writeable = False
        for mk in self.markers.values():
            mk.pos.flags.writeable = mk.rot.flags.writeable = False
        for given in (*self.placements.values(), *self.rates.values()):
            for arr in vars(given).values():
                if isinstance(arr, np.ndarray):
                    arr.flags.writeable = False
        self._moving = any(b.kind != "ground" for b in self.bodies.values())
        self._frozen = True

    def _working_copy(self):
        """A private copy for compiling and running (a CompiledModel's scene): its own bodies,
        markers, sensors and gravity, which a run's parameters change, and its own element
        records, which resolving user subroutines replaces; the same deck otherwise."""
        new = object.__new__(type(self))
        new.__dict__.update(self.__dict__)
        new.__dict__["_frozen"] = False
        new.gravity = self.gravity.copy()
        for element in catalogue.ELEMENTS:       # parameters change bodies, markers, sensors
            own = element.table in ("bodies", "markers", "sensors")
            new.__dict__[element.table] = {
                k: _copy(el) if own or getattr(el, "usersub", None) is not None else el
                for k, el in getattr(self, element.table).items()}
        new.usersub_paths, new.user_routines, new._scripts = {}, [], {}
        return new

    # public API -------------------------------------------------------------------------
    def run(self, progress: bool | None = None, stream: str | os.PathLike | None = None,
            params: dict | None = None, **options) -> Result:
        """Run the deck's commands in order and return a :class:`pysolver.Result`.

        Parameters
        ----------
        progress : bool or None, optional
            Show a progress bar on standard error. None (default) shows one only when standard
            error is a terminal and the run takes longer than one second.
        stream : str or os.PathLike, optional
            Write the rows to this CSV file (as :meth:`Result.save`) as they are made, so a
            crash (a C user subroutine's) loses none; complete when the run returns.
        params : dict, optional
            Numbers for this run only, by the sweep's paths (``{"Body_Point/2/mass": 2.0}``);
            no recompile; the next run has the deck's values. A bad one is a DeckError.
        **options
            Override the deck's ``Param_Transient`` and choose the linear solver, Jacobian,
            backend and kernel for this run (:class:`pysolver.options.Options`).

        Returns
        -------
        Result
            ``success=False`` with a message when the integration fails (never raises for
            that). Each call starts from the deck's initial state.

        Raises
        ------
        DeckError
            The deck has no moving body, or `params` names no number of this model.
        """
        moving = self.__dict__.get("_moving")     # known once loaded
        if not (moving if moving is not None else
                any(b.kind != "ground" for b in self.bodies.values())):
            self.check()                  # the DeckError saying there is nothing to run
        before = imports.spent()
        res = self.compile(options.get("kernel")).run(
            progress=progress, stream=None if stream is None else os.fspath(stream),
            params=params, **options)
        res.timing["imports"] = imports.spent() - before    # 0 once the process has them
        res._origin = (self, params)    # what res.animate() draws: no copy, no cost
        return res

    def compile(self, kernel: str | None = None):
        """The :class:`~pysolver.solve.compiled.CompiledModel` for a kind of kernel (as the
        ``kernel`` run option; None: ``PYSOLVER_KERNEL``, else auto), built once and kept."""
        kind = resolve_kernel(kernel)
        key = kind == "tapes"
        if key not in self._compiled:
            # the facade: compiling comes later (imported, and timed, only when building)
            with imports.timed():
                from .solve.compiled import CompiledModel
            self._compiled[key] = CompiledModel(self, kind)
        return self._compiled[key]

    @property
    def compiled_kernels(self) -> tuple:
        """The kinds of kernel compile() has built for this model so far."""
        return tuple(c.kind for c in self._compiled.values())

    def check(self):
        """Run every check a run makes before integrating: compile the kernel and check each
        Simulate command's output rows against the memory budget (PYSOLVER_OUTPUT_BUDGET).

        Raises
        ------
        DeckError
            The deck has no moving body, or a Simulate command's outputs would not fit (naming
            its file and line).
        """
        from .solve.outputs import command_rows, over_budget
        if not any(b.kind != "ground" for b in self.bodies.values()):
            raise DeckError("the deck has no moving body (a Body_Rigid that is not ground, or "
                            "a Body_Point): there is nothing to simulate",
                            file=self.source.file)
        kernel = self.compile().kernel
        t, rows = 0.0, 1
        for cmd in self.commands:
            if cmd.analysis == "TRANSIENT":
                rows += command_rows(t, cmd.end_time, cmd.print_interval)
                why = over_budget(rows, kernel.ny, len(kernel.channels),
                                  f"the Simulate command ending at {cmd.end_time:g}")
                if why:
                    raise DeckError(why, file=cmd.file or self.source.file, line=cmd.line,
                                    element="Simulate", attribute="print_interval")
            t = cmd.end_time if cmd.end_time is not None else t

    def summary(self) -> str:
        """Return a short human-readable listing of what the deck contains."""
        lines = [f"deck: {self.source.file} ({self.source.fmt})"]
        lines.append("units: " + (" ".join(f"{k}={v}" for k, v in self.units.items())
                                  if self.has_units else "consistent (no Units element)"))
        lines.append(f"gravity: {self.gravity.tolist()}")
        moving = [b for b in self.bodies.values() if b.kind != "ground"]
        lines.append(f"bodies: {len(moving)} moving "
                     f"({sum(b.kind == 'point' for b in moving)} point, "
                     f"{sum(b.kind == 'rigid' for b in moving)} rigid), "
                     f"{len(self.bodies) - len(moving)} ground")
        lines.append(f"markers: {len(self.markers)}")
        name = self._written
        for p in self.penalties.values():
            kind = "unilateral" if p.unilateral else "bilateral"
            lines.append(f"{name('penalty', p.id, 'Force_Penalty')} ({kind}): g = {p.text}")
        # a spring-damper (bushing) is held as the scalar (vector) force of the negative id:
        # listed as the deck wrote it, with its law and numbers
        for s in (s for s in self.sforces.values() if s.id > 0):
            lines.append(f"{name('sforce', s.id, 'Force_Scalar_TwoBody')} "
                         f"({'torque' if s.torque else 'force'} I={s.i} J={s.j}"
                         f"{', action only' if s.action_only else ''}): {s.text}")
        for sd in self.springdampers.values():
            lines.append(f"{name('springdamper', sd.id, 'Force_SpringDamper')} ({sd.type} "
                         f"I={sd.i} J={sd.j}): {self.sforces[-sd.id].text}; k={sd.stiffness:g}"
                         f" c={sd.damping:g} {'angle' if sd.type == 'ROTATIONAL' else 'length'}"
                         f"={sd.length:g} preload={sd.preload:g}")
        for vf in (vf for vf in self.vforces.values() if vf.id > 0):
            lines.append(f"{name('vforce', vf.id, 'Force_Vector_TwoBody')} (I={vf.i} "
                         + (f"J={vf.j} " if vf.j else "")
                         + f"in {vf.ref or 'global'}): ({', '.join(vf.texts)})")
        # a field's (beam's) law, held as a vector force under a negative key: its own name
        for vf in (vf for vf in self.vforces.values() if vf.id < 0 and vf.owner
                   and vf.owner[0] in ("Force_Field", "Force_Beam")):
            tag, eid = vf.owner
            lines.append(f"{name(tag[6:].lower(), eid, tag)} (I={vf.i} J={vf.j}, in J's axes): "
                         f"({', '.join(vf.texts)})")
        for bu in self.bushings.values():
            lines.append(f"{name('bushing', bu.id, 'Force_Bushing')} (I={bu.i} J={bu.j}, in "
                         f"J's axes): stiffness {_numbers(bu.stiffness)} damping "
                         f"{_numbers(bu.damping)} preload {_numbers(bu.preload)}")
        lines += [f"{name('loadcontrol', lc.id, 'LoadControl')}: body {lc.body} along "
                  f"{'xyz'[lc.direction]}, load {lc.load_text}, every {lc.update_time:g}"
                  for lc in self.controls.values()]
        lines += [f"{name('motion', mo.id, 'Motion_Joint' if mo.joint else 'Motion_Marker')} "
                  + (f"({mo.val_type} {'R' if mo.direction == 'B3' else 'T'} of joint "
                     f"{mo.joint}): " if mo.joint else
                     f"({mo.val_type} {mo.direction} I={mo.i} J={mo.j}): ")
                  + mo.text for mo in self.motions.values() if mo.id > 0]  # not LoadControl's
        lines += [f"{name('joint', jo.id, 'Constraint_Joint')} ({jo.type} I={jo.i} J={jo.j})"
                  for jo in self.joints.values()]
        lines += [f"{name('gcon', gc.id, 'Constraint_General')}: {gc.text} = 0"
                  for gc in self.gcons.values()]
        lines += [f"{name('coupler', cp.id, 'Constraint_Coupler')}: joints {cp.joints} "
                  f"({':'.join(cp.freedoms)}), scales {cp.scales}"
                  for cp in self.couplers.values()]
        lines += [f"{name('variable', v.id, 'Reference_Variable')}: {v.text}"
                  for v in self.variables.values()]
        lines += [f"{name('request', r.id, 'Post_Request')}: "
                  f"{sum(1 for t in r.texts if t)} channel(s)" for r in self.requests.values()]
        for se in self.sensors.values():
            lines.append(f"{name('sensor', se.id, 'Sensor_Event')}: {se.text} {se.compare} "
                         f"{se.value:g} (error_tol {se.error_tol:g}) -> "
                         f"{', '.join(se.actions()) or 'log'}")
        lines += [f"{name('evaluate', ev.id, 'Sensor_Evaluate')}: {ev.text}"
                  for ev in self.evaluates.values()]
        t = self.transient
        lines.append(f"Param_Transient: integr_tol={t.integr_tol:g} h_max={t.h_max} h_min="
                     f"{t.h_min:g} h0_max={t.h0_max}")
        st = self.static
        if any(c.analysis in ("STATIC", "QUASI-STATIC") for c in self.commands):
            lines.append(f"Param_Static: method={st.method} max_imbalance={st.max_imbalance:g} "
                         f"max_error={st.max_error:g} stability={st.stability:g}")
        for c in self.commands:
            lines.append(f"Simulate {c.analysis.lower()}: end_time={c.end_time:g}"
                         + (f" print_interval={c.print_interval:g}" if c.print_interval else ""))
        lines.append(self._states_line())
        return "\n".join(lines)

    def _written(self, kind, eid, tag):
        """How the deck wrote element `eid` of table `kind`: its element and id, and in an
        Adams dataset its statement, ``Force_SpringDamper 1 [SPRINGDAMPER/1]`` (`tag` when
        the model does not know where it came from)."""
        ctx = self._where.get((kind, eid))
        statement = (getattr(ctx, "names", None) or {}).get("#element")
        return f"{getattr(ctx, 'tag', None) or tag} {eid}" + (f" [{statement}]" if statement
                                                              else "")

    def _states_line(self):
        """The summary's state count: the 3-D model's, and once compiled (with its tracked
        angles) the count run (a planar scene's, or without redundant equations) when it
        differs."""
        full = self.num_states()
        compiled = next(iter(self._compiled.values()), None)
        if compiled is None:
            return f"states: {full}"
        layout = compiled.kernel.layout
        full += len(layout.turns)
        held = [f"body {bid}'s " + " and ".join("xyz"[a] for a in axes)
                for bid, axes in sorted(layout.held_axes.items())]
        more = len(held) - 3
        held = ", ".join(held[:3]) + (f" and {more} more bod{'y' if more == 1 else 'ies'}"
                                      if more > 0 else "")
        # held by a run with a dense matrix, the default below SPARSE_THRESHOLD states
        held = f" (IDA holds {len(layout.held)} at rest: {held})" \
            if layout.held and full < SPARSE_THRESHOLD else ""
        if compiled.kernel.ny == full:
            return f"states: {full}{held}"
        why = "a planar scene" if layout.planar else "redundant equations left out"
        return f"states: {compiled.kernel.ny} integrated ({full} in 3-D; {why})"

    def num_states(self) -> int:
        """IDA states of the 3-D model: 6 per point body, 13 per rigid body, 1 per motion (2 for
        a displacement or an acceleration), 2 per joint equation, per Constraint_General and
        per Constraint_Coupler (its reactions at the velocity and the position level). The
        tracked angles (one per AX..AZ an expression reads, rotational spring, coupled
        rotation, SCREW or RACK_PINION: docs/deck-language.md, "Tracked angles") are known
        once compiled, and :meth:`summary` counts them then. A planar scene runs with fewer
        (6 per body, 4 per revolute: docs/numerics.md, "Planar scenes"); redundant equations
        are left out too; ``model.compile().kernel.ny`` is the count run."""
        return (sum({"point": 6, "rigid": 13}.get(b.kind, 0) for b in self.bodies.values())
                + sum(1 + (m.val_type != "V") for m in self.motions.values())
                + sum(2 * len(catalogue.JOINT_EQUATIONS[j.type]) for j in self.joints.values())
                + 2 * len(self.gcons) + 2 * len(self.couplers))

    def __reduce__(self):
        return (_rebuild, (self.source.file, self.source.text, self.source.fmt,
                           self.source.user_code, self.source.simulate))


def _rebuild(file, text, fmt, user_code=True, simulate=None):
    from .deck.loader import loads
    return loads(text, fmt=fmt, file=file, user_code=user_code, simulate=simulate)



def _numbers(values):
    """Six numbers of a bushing as the summary lists them: ``(10, 10, 10, 0, 0, 0)``."""
    return "(" + ", ".join(f"{v:g}" for v in values) + ")"
