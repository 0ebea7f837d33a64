"""Integrator options: the settings of ``Param_Transient`` and the run-time choices, defined once.

One :class:`Options` object carries every option from the deck (``Param_Transient``, Python
``INTEGRATOR``) through :meth:`pysolver.Model.run` overrides to the IDA driver and the static
solvers. Names, defaults, rules and documentation live here and nowhere else; ``None`` means
"not set" (the consumer's documented default applies).
"""
from __future__ import annotations

import dataclasses
import numbers
from typing import Optional

from . import settings

#: With ``linsolver="auto"``, scenes with at least this many states use a sparse or band solver.
SPARSE_THRESHOLD = 300

#: The C driver's step-growth limit once IDA's error test fails in most steps (a stiff penalty
#: mode, docs/stiff-penalties.md), and its default Newton convergence coefficient. IDA's own is
#: 0.33; ten times tighter costs nothing on the seed decks and halves the steps of stiff
#: penalties. Near the limit of double precision (penalty/mass ~ 1e14) rounding keeps Newton
#: from reaching it and 0.33 must be asked for.
AUTO_STEP_GROWTH = 1.1
NONLIN_CONV_COEF = 0.033

#: Rules beyond the type: (test, text) per option; the text completes "must be ..." and
#: "expected a value ...".
_RULES = {
    # below 1e-14 rounding of the state is larger than the tolerance; above 1 nothing is controlled
    "integr_tol": (lambda v: 1e-14 <= v <= 1, "in [1e-14, 1]"),
    "h_max": (lambda v: v > 0, "> 0"),
    "h_min": (lambda v: v >= 0, ">= 0"),
    "h0_max": (lambda v: v > 0, "> 0"),
    # IDA counts steps in a C long; past 1e15 a budget means nothing
    "max_num_steps": (lambda v: 0 < v <= 1e15 and float(v).is_integer(),
                      "a whole number in [1, 1e15]"),
    "max_step_growth": (lambda v: v > 1, "> 1"),
    "nonlin_conv_coef": (lambda v: 0 < v < 1, "in (0, 1)"),
}
_CHOICES = {"linsolver": ("auto", "dense", "band", "sparse", "superlu_mt", "sundials_dense"),
            "jacobian": ("exact", "dq"), "backend": ("auto", "c", "sksundae"),
            "kernel": ("auto", "generated", "tapes"), "reactions": ("exact", "integrator")}


@dataclasses.dataclass(frozen=True)
class Options:
    """How a model is integrated.

    The first seven fields are ``Param_Transient``'s attributes (same names, units of the
    deck); the last five are run-time choices. Change them per run with
    ``model.run(name=value, ...)``.

    Attributes
    ----------
    integr_tol : float, default 1e-3
        IDA's relative and absolute tolerance; absolute in the deck's units, so a deck whose
        states are small numbers in its units (ms, µs) needs a smaller one
        (docs/deck-language.md, "integr_tol is absolute in the deck's units").
    h_max : float or None
        Largest step; None: unbounded.
    h_min : float, default 0
        Smallest step.
    h0_max : float or None
        Largest first step; None: IDA's choice.
    max_num_steps : int, default 1000000
        Most steps in one Simulate command.
    max_step_growth : float or None
        Largest factor by which IDA may grow its step (> 1). None: IDA's 2 until its error
        test fails in most of 50 steps (a stiff penalty mode), then 1.1. C driver only.
    nonlin_conv_coef : float or None
        IDA's Newton convergence coefficient in (0, 1). None: 0.033 on the C driver, IDA's
        0.33 on scikit-sundae.
    linsolver : {"auto", "dense", "band", "sparse", "superlu_mt", "sundials_dense"}
        "auto": dense below 300 states, sparse above. "dense": on the C driver pysolver's own
        dense LU (through scikit-sundae, SUNDIALS' dense solver). "sparse": compressed sparse
        columns factored by pysolver's sparse LU on the C driver (SciPy's SuperLU through
        scikit-sundae); "band": IDA's band solver with the Jacobian's bandwidths (C driver);
        "superlu_mt": SUNDIALS' SuperLU_MT (C driver); "sundials_dense": SUNDIALS' dense
        solver on the C driver too. The last three for comparison: the sparse LU is as fast
        as the band solver on chains and faster than SuperLU_MT (docs/numerics.md, "The
        sparse LU"), and the dense LU faster than SUNDIALS' dense one.
    jacobian : {"exact", "dq"}
        The kernel's exact iteration matrix, or IDA's difference quotients (comparison only).
    backend : {"auto", "c", "sksundae"} or None
        IDA driven from C, or through scikit-sundae's Python callbacks. None: the
        ``PYSOLVER_BACKEND`` environment variable, else "auto" (C where the scene allows).
    kernel : {"auto", "generated", "tapes"} or None
        The scene's generated C (compiled once per deck, cached on disk; "auto" and
        "generated" fall back to the tapes, with a log line, when no C compiler works), or the
        tape interpreter. None: the
        ``PYSOLVER_KERNEL`` environment variable, else "auto".
    reactions : {"exact", "integrator"}
        "exact": each output row's accelerations and reactions (JOINT, MOTION, res.joint, ACC*)
        solved at its positions and velocities (a saddle-point system per row, costing
        1.0-1.4x the run on the joint example decks); "integrator": IDA's corrector values,
        which its error test does not hold (percents of noise at integr_tol 1e-3).
    """
    integr_tol: float = 1e-3
    h_max: Optional[float] = None
    h_min: float = 0.0
    h0_max: Optional[float] = None
    max_num_steps: int = 1000000
    max_step_growth: Optional[float] = None
    nonlin_conv_coef: Optional[float] = None
    linsolver: str = "auto"
    jacobian: str = "exact"
    backend: Optional[str] = None
    kernel: Optional[str] = None
    reactions: str = "exact"

    def __post_init__(self):
        for name in _RULES:
            problem = rule_problem(name, getattr(self, name))
            if problem:
                raise ValueError(f"{name} must be {problem}")
        problem = steps_problem(self.h_min, self.h_max)
        if problem:
            raise ValueError(problem)
        # a whole number given as 5000.0 or a NumPy integer is the C long it goes to
        object.__setattr__(self, "max_num_steps", int(self.max_num_steps))
        for name, allowed in _CHOICES.items():
            value = getattr(self, name)
            if value is not None and value not in allowed:
                raise ValueError(f"{name} must be {', '.join(map(repr, allowed))}, "
                                 f"not {value!r}")

    def replace(self, **changes) -> "Options":
        """Return a copy with some options changed (checked like the constructor).

        Raises
        ------
        TypeError
            An unknown option name.
        ValueError
            A value that breaks its option's rule, or is not a number where one is expected
            (a string such as ``"1e-6"`` included).
        """
        unknown = sorted(set(changes) - set(NAMES))
        if unknown:
            raise TypeError(f"unknown run option {unknown[0]!r}; expected one of "
                            f"{', '.join(NAMES)}")
        return dataclasses.replace(self, **changes)

    def resolved_backend(self) -> str:
        """The backend asked for: the option, else ``PYSOLVER_BACKEND``, else "auto"."""
        backend = self.backend or settings.backend() or "auto"
        if backend not in _CHOICES["backend"]:
            raise ValueError(f"backend must be 'auto', 'c' or 'sksundae', not {backend!r}")
        return backend

    def resolved_kernel(self) -> str:
        """The kernel asked for: the option, else ``PYSOLVER_KERNEL``, else "auto"."""
        return resolve_kernel(self.kernel)


NAMES = tuple(f.name for f in dataclasses.fields(Options))
#: The options a deck's Param_Transient sets.
DECK_NAMES = NAMES[:7]


#: Param_Transient's settings that act on transient commands only: a static or quasi-static
#: command (FIM_S, MKEAM, FIM_D) takes integr_tol alone (docs/statics.md).
TRANSIENT_ONLY = ("h_max", "h_min", "h0_max", "max_num_steps", "max_step_growth",
                  "nonlin_conv_coef")


def transient_only(options):
    """The settings of TRANSIENT_ONLY that `options` (an Options, or a dict of some of them)
    sets to other than their defaults."""
    default = Options()
    if isinstance(options, dict):
        return [n for n in TRANSIENT_ONLY if n in options and options[n] != getattr(default, n)]
    return [n for n in TRANSIENT_ONLY if getattr(options, n) != getattr(default, n)]


def steps_problem(h_min, h_max):
    """Why the step bounds h_min and h_max (None: unbounded) cannot both hold, or None."""
    if h_max is not None and h_min is not None and h_min > h_max:
        return (f"h_min ({h_min:g}) > h_max ({h_max:g}): the smallest step IDA may take is "
                "larger than the largest")
    return None


def resolve_kernel(kind):
    """The kernel option `kind` (None: ``PYSOLVER_KERNEL``, else "auto"), checked."""
    kind = kind or settings.kernel() or "auto"
    if kind not in _CHOICES["kernel"]:
        raise ValueError(f"kernel must be 'auto', 'generated' or 'tapes', not {kind!r}")
    return kind


def rule_problem(name, value):
    """Text of the rule `value` breaks for option `name` (e.g. "> 1"), or None if it is fine."""
    if value is None or name not in _RULES:
        return None
    test, text = _RULES[name]
    shown = repr(value) if len(repr(value)) <= 40 else repr(value)[:37] + "..."
    kind = text if text.startswith("a ") else "a number " + text
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return f"{kind}, not {shown}"
    try:
        float(value)
    except OverflowError:               # an int past any float
        return f"{kind}, not {shown}"
    return None if test(value) else text
