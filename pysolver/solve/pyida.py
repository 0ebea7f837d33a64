"""scikit-sundae's IDA behind the integrator interface of :mod:`.integrator`.

Used for scenes the C driver does not take (large non-banded ones, ``jacobian="dq"``, no
SUNDIALS libraries) and for the static solvers' own DAEs (MKEAM's kinetic-energy peaks, FIM_D's
equilibrium path), whose residuals are Python functions. Everything scikit-sundae-specific is
here: its callback signatures, its event bookkeeping and the counters it reports.
"""
import warnings

import numpy as np

from .. import imports
from ..build.kernel import UserFailure
from .step import ROOT_RETURN, Step

#: IDA's flag for a residual that failed unrecoverably.
UNRECOVERABLE = -8


class PyIDA:
    """An IDA object of scikit-sundae with the interface of :class:`~.cida.CIDA`.

    Parameters
    ----------
    resfn : callable ``resfn(t, y, yp, res)``
    rootfn : callable ``rootfn(t, y, yp, g)`` or None
        Root functions; an event is a crossing from negative to positive.
    nroots : int
    rtol, atol : float
    max_step, min_step, first_step : float
        0 for IDA's defaults.
    max_num_steps : int
    outputs : callable ``outputs(t, y, yp) -> ndarray`` or None
        Request channels written by :meth:`outputs` (a kernel's); None: no channels.
    nout : int
        Number of channels ``outputs`` returns.
    hit_outputs : bool
        End a step at every requested time (a model with reactions: its constraints hold at
        steps, not on IDA's interpolant), as the C driver does.
    **lin
        scikit-sundae's linear-solver options: ``linsolver``, ``jacfn``, ``sparsity``,
        ``algebraic_idx``.
    """

    def __init__(self, resfn, rootfn=None, nroots=0, rtol=1e-3, atol=1e-3, max_step=0.0,
                 min_step=0.0, first_step=0.0, max_num_steps=500, outputs=None, nout=0,
                 hit_outputs=False, **lin):
        options = dict(rtol=rtol, atol=atol, max_step=max_step, min_step=min_step,
                       first_step=first_step, max_num_steps=max_num_steps, **lin)
        self._events = None
        if rootfn is not None and nroots:
            ev = lambda t, y, yp, g: rootfn(t, y, yp, g)  # noqa: E731
            ev.direction = [1] * nroots
            ev.terminal = [True] * nroots
            options.update(eventsfn=ev, num_events=nroots)
            self._events = ev
        self._outputs, self._nout = outputs, nout
        self._hit = hit_outputs
        self._ny = None
        self._done = [0, 0]          # nfev, njev of earlier starts (scikit-sundae resets them)
        self._last = (0, 0)
        with warnings.catch_warnings():
            # scikit-sundae warns that an exact sparse jacfn replaces its DQ Jacobian
            warnings.simplefilter("ignore", UserWarning)
            with imports.timed():       # scikit-sundae (and scipy.optimize): only here
                from sksundae.ida import IDA
            self._ida = IDA(resfn, **options)

    def init_step(self, t0, y0, yp0):
        """Start (or cold-restart) at (t0, y0, yp0)."""
        self._done[0] += self._last[0]
        self._done[1] += self._last[1]
        self._last = (0, 0)
        self._forget_events()
        self._ny = len(y0)
        self._ida.init_step(t0, y0, yp0)

    def _forget_events(self):
        # scikit-sundae keeps every event in lists on the events function and rebuilds its
        # result from them at each step; the driver needs only the newest one, so clearing
        # keeps a step's cost independent of how many events came before
        for name in ("_i", "_t", "_y", "_yp"):
            lst = getattr(self._events, name, None)
            if isinstance(lst, list):
                lst.clear()

    def interpolate(self, t, tstop):
        """The state at t, which the last step passed (scikit-sundae has no interpolant of
        its own to call: a normal-mode call toward t)."""
        return self.step(t, tstop)

    def step(self, tout, tstop=None, onestep=False):
        """One IDASolve call toward tout, never past tstop (None: no limit); with reactions
        (algebraic states) a step ends at tout, as in csrc/ida.c."""
        if self._hit and not onestep and (tstop is None or tout < tstop):
            tstop = tout
        try:
            sol = self._ida.step(tout, method="onestep" if onestep else "normal", tstop=tstop)
        except UserFailure:             # the kernel holds the subroutine's message
            return Step(float(tout), np.full(self._ny, np.nan), np.full(self._ny, np.nan),
                        UNRECOVERABLE)
        self._last = (int(sol.nfev), int(sol.njev))
        roots = None
        if sol.status == ROOT_RETURN:
            roots = np.array(sol.i_events[-1], dtype=np.int32)
            self._forget_events()
        return Step(float(sol.t), np.array(sol.y), np.array(sol.yp), int(sol.status), roots)

    def outputs(self, times, tstop):
        """Advance through output times (one Python call each); see CIDA.outputs."""
        Y, YP, REQ = [], [], []
        step = None
        for tp in times:
            step = self.step(tp, tstop)
            if not step.success or step.status == ROOT_RETURN:
                break
            try:
                out = self._outputs(step.t, step.y, step.yp) if self._outputs else np.zeros(0)
            except UserFailure:         # a routine failed at the row: the run ends there
                step = Step(step.t, step.y, step.yp, UNRECOVERABLE)
                break
            Y.append(step.y)
            YP.append(step.yp)
            REQ.append(out)
        n = len(Y)
        shape = (0, len(step.y) if step else 0)
        return (step, np.array(Y) if n else np.zeros(shape), np.array(YP) if n else np.zeros(shape),
                np.array(REQ) if n else np.zeros((0, self._nout)), n)

    def counters(self):
        """IDA's residual and Jacobian calls over this object's life; scikit-sundae reports no
        step or failure counters (None)."""
        return {"steps": None, "nfev": self._done[0] + self._last[0],
                "njev": self._done[1] + self._last[1], "netf": None, "ncfn": None,
                "growth_limited_at": None}
