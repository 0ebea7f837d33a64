"""A Model compiled to run: :meth:`pysolver.Model.compile` returns one.

The :class:`CompiledModel` owns what compiling made and what runs keep: the kernel (generated C
or the tapes) with the user routines it calls, MKEAM's undamped twin (built on first use), the
numbers a run may change without recompiling (:class:`~pysolver.build.params.Parameters`), and
the caches of runs (their settings, integration plans, the batched path's IDA object). A Model
holds one CompiledModel per kind of kernel; ``model.run(...)`` is ``model.compile().run(...)``.
"""
import numpy as np

from .. import settings
from ..build import Kernel
from ..build.consistent import AssemblyError, redundant
from ..build.kernel import UserFailure, follow
from ..build.params import Parameters
from ..build.planar import looks_planar
from ..build.planar import why_not as why_not_planar
from .run import run_model


class CompiledModel:
    """A Model compiled for one kind of kernel.

    Parameters
    ----------
    model : pysolver.Model
    kind : {"auto", "generated", "tapes"}
        Options.kernel, resolved (see :meth:`pysolver.options.Options.resolved_kernel`).

    Attributes
    ----------
    model : pysolver.Model
        The scene as compiled: a private copy of the loaded model, its user subroutines
        resolved into expressions or kernel calls.
    kernel : pysolver.build.kernel.Kernel
        The compiled scene bound to the C kernel.
    """

    def __init__(self, model, kind):
        # the scene compiled and run: a private copy of the model (user subroutines resolve
        # into it, parameters change it), the model itself never changes
        self.model, self.kind = model._working_copy(), kind
        self.kernel = self._kernel_without_redundancy(kind)
        self._conservative = None
        self._parameters = None
        # kept between runs: the last run's settings (solve.run), plans (solve.integrator)
        # and batched runs (solve.fast), each keyed by what it depends on
        self.run_settings = None
        self.plans = {}
        self.batched = {}

    def _kernel_without_redundancy(self, kind):
        """The kernel, joint equations that repeat others left out (found on the tapes at
        the assembled initial positions; :attr:`notes` names them)."""
        self.removed, self.notes = (), []
        if not (self.model.joints or self.model.gcons or self.model.couplers):
            return Kernel(self.model, False, kind)
        probe = Kernel(self.model, False, "tapes")
        try:
            self.removed = redundant(probe, 0.0, probe.layout.initial_state())
        except (AssemblyError, np.linalg.LinAlgError, ValueError, ArithmeticError,
                UserFailure):
            pass                          # each run says why (solve.driver.start_state)
        if self.removed:
            per = {}
            for kind, cid, k in self.removed:
                per.setdefault((kind, cid), []).append(str(k + 1))
            tag = {"joint": "Constraint_Joint", "gcon": "Constraint_General",
                   "coupler": "Constraint_Coupler"}
            eqs = "; ".join(f"{tag[kind]} {cid}" + ("" if kind != "joint" else
                                                    f" equation{'s' * (len(ks) > 1)} "
                                                    f"{', '.join(ks)}")
                            for (kind, cid), ks in per.items())
            self.notes.append(f"redundant constraints removed ({len(self.removed)}): {eqs}")
        n = len(probe.layout.planar)
        if n:
            self.notes.append(f"planar scene: {n} bod{'y' if n == 1 else 'ies'} integrated in "
                              "(x, y, rz), the revolutes' out-of-plane equations left out "
                              "(docs/numerics.md, \"Planar scenes\")")
        elif looks_planar(self.model):
            self.notes.append(f"not a planar scene, integrated in 3-D: {why_not_planar(self.model)}"
                              if settings.planar() else "integrated in 3-D: PYSOLVER_PLANAR=off")
        if kind == "tapes" and not self.removed:
            return probe
        kernel = Kernel(self.model, False, kind, self.removed)
        # the equations left out are checked on the run's rows (solve.kept) with the probe,
        # which holds them all
        kernel.redundancy = (probe, self.removed) if self.removed else None
        return kernel

    @property
    def conservative_kernel(self):
        """The kernel without velocity-dependent terms, for MKEAM (built on first use), with
        the numbers of the run in progress (params=, a sweep's case) copied from the run's
        kernel each time it is asked for."""
        if self._conservative is None:
            self._conservative = Kernel(self.model, True, self.kind, self.removed)
        follow(self._conservative, self.kernel)
        return self._conservative

    @property
    def parameters(self):
        """The numbers a run may change without recompiling (the sweep's paths)."""
        if self._parameters is None:
            self._parameters = Parameters(self.model, self.kernel)
        return self._parameters

    def run(self, progress=None, stream=None, params=None, **options):
        """Run the model's commands; see :meth:`pysolver.Model.run`."""
        if not params:
            return run_model(self, progress=progress, overrides=options, stream=stream)
        case_options = self.parameters.apply(params)
        try:
            return run_model(self, progress=progress, overrides={**case_options, **options},
                             stream=stream)
        finally:
            self.parameters.reset()
