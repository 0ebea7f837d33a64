"""The validated scene: plain records of its elements, and the :class:`Model` that holds them.
The deck readers (:mod:`pysolver.deck`) build it, :mod:`pysolver.build` lays it out for the
C kernel, :mod:`pysolver.solve` runs it; :meth:`Model.run` imports those stages when called.
"""
from __future__ import annotations

import dataclasses
import functools
import hashlib
import os
from typing import TYPE_CHECKING

import numpy as np

from .errors import DeckError
from .options import Options

if TYPE_CHECKING:               # for annotations only: results come later in the flow
    from .results import Result

#: Units of a deck without a ``Units`` element.
UNIT_DEFAULTS = {"mass": "KILOGRAM", "length": "METER", "time": "SECOND", "force": "NEWTON"}


@dataclasses.dataclass
class Marker:
    id: int
    body: int              # body id (ground id for ground markers)
    pos: np.ndarray        # global position at t = 0
    rot: np.ndarray        # global axes at t = 0 (columns x, y, z)
    label: str = ""


@dataclasses.dataclass
class Body:
    id: int
    kind: str              # "ground", "point" or "rigid"
    mass: float = 0.0
    inertia: np.ndarray = None   # body-frame inertia tensor (3 x 3)
    pos: np.ndarray = None       # initial position of the body frame origin (the cg marker)
    rot: np.ndarray = None       # initial body axes (columns)
    vel: np.ndarray = None       # initial velocity, global
    omega: np.ndarray = None     # initial angular velocity, body frame
    label: str = ""
    cg: int = None               # its centre-of-mass marker (the body frame)
    im_rot: np.ndarray = None    # axes of the inertia marker in the body frame
    inertia_im: np.ndarray = None    # inertia as the deck gives it, about the im axes


@dataclasses.dataclass
class UserSub:
    """A user subroutine standing in for an element's expression (``type="USERSUB"``).

    Until it is resolved into an expression tree (pysolver.deck.usersub, when the model is first
    compiled) the element's ``expr`` is None.
    """
    name: str              # the conventional name: PFOSUB, SENSUB, SEVSUB, VARSUB, SFOSUB, REQSUB
    routine: object        # function name in the script or library, or a Python callable
    par: tuple             # the numbers of USER(p1, ..., pn)
    script: str = None     # path of a Python script defining the routine
    library: str = None    # path of a C shared library defining it
    attribute: str = "usrsub_fnc_name"   # the deck attribute to name in errors
    untraced: str = None   # why a Python routine could not be traced (it is called instead)

    def describe(self):
        """A short text for summaries and logs."""
        where = self.script or self.library or "a Python callable"
        name = self.routine if isinstance(self.routine, str) else \
            getattr(self.routine, "__name__", "routine")
        return f"USER({', '.join(f'{p:g}' for p in self.par)}) -> {name} ({where})"


@dataclasses.dataclass
class Penalty:
    id: int
    expr: tuple
    text: str
    penalty: float
    penalty1: float
    unilateral: bool
    smoothing: float
    label: str = ""
    usersub: UserSub = None


@dataclasses.dataclass
class ScalarForce:
    id: int
    torque: bool
    i: int
    j: int
    expr: tuple
    text: str
    label: str = ""
    usersub: UserSub = None


@dataclasses.dataclass
class VectorForce:
    """Force_Vector_TwoBody: a force with components exprs (x, y, z of marker `ref`; None or 0:
    global axes) on I's body at I, and its opposite on J's body at the same point (J is the
    floating marker: only its body matters)."""
    id: int
    i: int
    j: int
    ref: int
    exprs: list
    texts: list
    label: str = ""


@dataclasses.dataclass
class Motion:
    """Motion_Marker: the displacement (D), velocity (V) or acceleration (A) of marker I
    relative to J along one axis of J (X, Y, Z: DX/DY/DZ(I, J, J)) or about it (B1, B2, B3:
    AX/AY/AZ(I, J)) follows expr, a function of time."""
    id: int
    i: int
    j: int
    direction: str
    val_type: str
    expr: tuple
    text: str
    label: str = ""


@dataclasses.dataclass
class LoadControl:
    """The LoadControl task (seed 002): every update_time, the velocity of `body` along global
    axis `direction` (0, 1, 2) is set so that the load on it follows `load_expr` (a function of
    time). The body is driven by the velocity motion `motion` (a Motion in Model.motions whose
    expression is the controller's output)."""
    id: int
    body: int
    direction: int
    velocity: float
    max_velocity: float
    load_expr: tuple
    load_text: str
    kp: object                  # a number or "auto"
    ki: object
    smooth: float
    update_time: float
    median_window: int
    motion: int
    load: str = "REACTION"      # or "CONTACT": the penalties' force on the body
    label: str = ""


@dataclasses.dataclass
class Variable:
    id: int
    expr: tuple
    text: str
    label: str = ""
    usersub: UserSub = None


@dataclasses.dataclass
class Request:
    id: int
    exprs: list            # 8 entries: parse tree or None
    texts: list
    names: list
    label: str = ""
    usersub: UserSub = None


@dataclasses.dataclass
class Sensor:
    """A Sensor_Event: watch ``expr`` against ``value`` and act when it fires."""
    id: int
    expr: tuple
    text: str
    value: float
    compare: str           # "GE", "LT" or "EQ" (Adams' LE reads as LT)
    error_tol: float
    evaluate_id: int = None
    dt: float = None
    stepsize: float = None
    zero_crossing: float = None
    hmax: float = None
    halt: bool = False
    print: bool = False
    restart: bool = False
    verbose: bool = False
    ret: bool = False
    label: str = ""
    usersub: UserSub = None

    def actions(self):
        """Names of the actions this sensor takes when it fires, in the order they run."""
        names = []
        for key in ("evaluate_id", "dt", "stepsize", "hmax", "zero_crossing"):
            if getattr(self, key) is not None:
                names.append(key)
        for key in ("restart", "print", "verbose", "halt"):
            if getattr(self, key):
                names.append(key)
        if self.ret:
            names.append("return")
        return names


@dataclasses.dataclass
class Evaluate:
    """A Sensor_Evaluate: stored when a parent sensor fires, read by SENVAL(id)."""
    id: int
    expr: tuple
    text: str
    label: str = ""
    usersub: UserSub = None


@dataclasses.dataclass
class Static:
    """Settings of ``Param_Static`` (seed 004 defaults); see :mod:`pysolver.solve.statics`."""
    method: str = "FIM_D"
    max_ke_tol: float = 1e-5
    max_dq_tol: float = 1e-3
    max_num_iter: int = 100
    max_imbalance: float = 1e-4
    max_error: float = 1e-4
    stability: float = 1e-10
    compliance_delta: float = 1e-3
    tlimit: float = 20.0               # pysolver extension: Adams' TLIMIT, length units
    alimit: float = 0.17453292519943295  # pysolver extension: Adams' ALIMIT (10 deg), radians


@dataclasses.dataclass
class Simulate:
    analysis: str
    end_time: float
    print_interval: float
    line: int = None


@dataclasses.dataclass
class Source:
    """Where a deck came from, for error messages and result metadata."""
    file: str
    text: str
    fmt: str
    user_code: bool = True      # False: loaded with user_code=False (it names no code to run)

    @functools.cached_property
    def sha256(self):
        return hashlib.sha256(self.text.encode()).hexdigest()

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
        self.markers = {}
        self.bodies = {}
        self.penalties = {}
        self.sforces = {}
        self.vforces = {}
        self.motions = {}
        self.controls = {}        # LoadControl tasks by id
        self.variables = {}
        self.requests = {}
        self.sensors = {}
        self.evaluates = {}
        self.transient = Options()      # Param_Transient
        self.static = Static()
        self.commands = []
        self.has_units = False
        self._compiled = {}       # CompiledModel by kind of kernel (compile)
        self.usersub_paths = {}   # element -> how its user subroutine runs (filled when compiled)
        self.user_routines = []   # routines the kernel calls (pysolver.build.usercalls)
        self._scripts = {}        # user subroutine scripts run so far: path -> namespace
        self._where = {}          # (kind, id) -> location of the element, for errors

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
        if not any(b.kind != "ground" for b in self.bodies.values()):
            self.check()                  # the DeckError saying there is nothing to run
        return self.compile(options.get("kernel")).run(
            progress=progress, stream=None if stream is None else os.fspath(stream),
            params=params, **options)

    def compile(self, kernel: str | None = None):
        """The :class:`~pysolver.solve.compiled.CompiledModel` for a kind of kernel (as the
        ``kernel`` run option; None: ``PYSOLVER_KERNEL``, else auto), built once and kept."""
        from .solve.compiled import CompiledModel  # the facade: compiling comes later
        kind = Options(kernel=kernel).resolved_kernel()
        key = kind == "tapes"
        if key not in self._compiled:
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
                    raise DeckError(why, file=self.source.file, line=cmd.line,
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
        for p in self.penalties.values():
            kind = "unilateral" if p.unilateral else "bilateral"
            lines.append(f"Force_Penalty {p.id} ({kind}): g = {p.text}")
        for s in self.sforces.values():
            lines.append(f"Force_Scalar_TwoBody {s.id} ({'torque' if s.torque else 'force'} "
                         f"I={s.i} J={s.j}): {s.text}")
        for vf in self.vforces.values():
            lines.append(f"Force_Vector_TwoBody {vf.id} (I={vf.i} J={vf.j} in "
                         f"{vf.ref or 'global'}): ({', '.join(vf.texts)})")
        lines += [f"LoadControl {lc.id}: body {lc.body} along {'xyz'[lc.direction]}, load "
                  f"{lc.load_text}, every {lc.update_time:g}" for lc in self.controls.values()]
        lines += [f"Motion_Marker {mo.id} ({mo.val_type} {mo.direction} I={mo.i} J={mo.j}): "
                  f"{mo.text}" for mo in self.motions.values() if mo.id > 0]  # not LoadControl's
        lines += [f"Reference_Variable {v.id}: {v.text}" for v in self.variables.values()]
        lines += [f"Post_Request {r.id}: {sum(1 for t in r.texts if t)} channel(s)"
                  for r in self.requests.values()]
        for se in self.sensors.values():
            lines.append(f"Sensor_Event {se.id}: {se.text} {se.compare} {se.value:g} "
                         f"(error_tol {se.error_tol:g}) -> {', '.join(se.actions()) or 'log'}")
        lines += [f"Sensor_Evaluate {ev.id}: {ev.text}" for ev in self.evaluates.values()]
        t = self.transient
        lines.append(f"Param_Transient: integr_tol={t.integr_tol:g} h_max={t.h_max} h_min="
                     f"{t.h_min:g} h0_max={t.h0_max}")
        st = self.static
        if any(c.analysis != "TRANSIENT" for c in self.commands):
            lines.append(f"Param_Static: method={st.method} max_imbalance={st.max_imbalance:g} "
                         f"max_error={st.max_error:g} stability={st.stability:g}")
        for c in self.commands:
            lines.append(f"Simulate {c.analysis.lower()}: end_time={c.end_time:g}"
                         + (f" print_interval={c.print_interval:g}" if c.print_interval else ""))
        lines.append(f"states: {self.num_states()}")
        return "\n".join(lines)

    def num_states(self) -> int:
        """IDA states: 6 per point body, 13 per rigid body, 1 per motion (2 for acceleration)."""
        return (sum({"point": 6, "rigid": 13}.get(b.kind, 0) for b in self.bodies.values())
                + sum(1 + (m.val_type == "A") for m in self.motions.values()))

    def __reduce__(self):
        return (_rebuild, (self.source.file, self.source.text, self.source.fmt,
                           self.source.user_code))


def _rebuild(file, text, fmt, user_code=True):
    from .deck.loader import loads
    return loads(text, fmt=fmt, file=file, user_code=user_code)

