"""The sensors as the batched path's C loop decides them (csrc/events.c, csrc/ida.c's
``ps_ida_controlled``): the ``psSensors`` struct, its arrays and its remembered steps, and its
event records turned into :class:`~.sensors.Event` objects and log lines as
:class:`~.sensors.Sensors` writes them (tests/test_fast.py holds the two to the bit)."""
import numpy as np

from . import sensors as _rules
from .sensors import CHATTER_LIMIT, Event, dense_yp, whole_restart


class CSensors:
    """A deck's sensors as the C loop decides them (``psSensors``): the struct, its arrays, and
    its event records turned into :class:`Event` objects and log lines as :class:`Sensors`
    writes them. `cap` events (default :data:`.sensors.EVENT_CAP`) are kept in C between drains."""

    def __init__(self, model, kernel, cap=None):
        from ..build.bindings import ffi, lib
        self.kernel = kernel
        self.sensors = [model.sensors[i] for i in kernel.sensor_ids]
        n = len(self.sensors)
        eidx = {eid: i for i, eid in enumerate(kernel.evaluate_ids)}
        slots = [eidx[se.evaluate_id] if se.evaluate_id is not None else -1
                 for se in self.sensors]
        tapes = [kernel.evaluate_tapes[i] if i >= 0 else (0, 0) for i in slots]
        ints = {"evaluate": slots, "eval_tape": [t for t, _ in tapes],
                "eval_slot": [s for _, s in tapes], "halts": [se.halt for se in self.sensors],
                "restarts": [se.restart for se in self.sensors],
                "prints": [se.print for se in self.sensors],
                "rets": [se.ret for se in self.sensors],
                "verboses": [se.verbose for se in self.sensors]}
        cap = max(cap or _rules.EVENT_CAP, n)
        self.S = S = ffi.new("psSensors *")
        self.keep = []

        def array(values, kind):
            arr = np.ascontiguousarray(values, dtype=np.int32 if kind == "int" else float)
            self.keep.append(arr)
            return ffi.cast(f"{kind} *", ffi.from_buffer(arr))
        for name, values in ints.items():
            setattr(S, name, array(values, "int"))
        for name in ("holds", "rearms", "fired", "rearmed", "now", "roots", "verbose_on"):
            setattr(S, name, array(np.zeros(n), "int"))
        S.f = array(np.zeros(n), "double")
        S.dts = array([se.dt or 0.0 for se in self.sensors], "double")
        S.hmaxs = array([se.hmax or 0.0 for se in self.sensors], "double")
        S.stepsizes = array([se.stepsize or 0.0 for se in self.sensors], "double")
        S.n, S.nverbose = n, sum(se.verbose for se in self.sensors)
        # zero_crossing: the factors, the searches under way, the remembered steps
        S.zcs = array([se.zero_crossing or 0.0 for se in self.sensors], "double")
        S.nzc = sum(se.zero_crossing is not None for se in self.sensors)
        S.zc_pending = array(np.zeros(n), "int")
        snaps, ny, ns = lib.PS_SNAPS, kernel.ny, len(kernel.senval)
        S.nsenval = ns
        for name in ("snap_t", "snap_hmax", "snap_interval", "snap_anchor"):
            setattr(S, name, array(np.zeros(snaps), "double"))
        for name in ("snap_nrearms", "snap_records"):
            arr = np.zeros(snaps, dtype=np.int64)
            self.keep.append(arr)
            setattr(S, name, ffi.cast("long *", ffi.from_buffer(arr)))
        S.snap_y, S.snap_yp = (array(np.zeros(snaps * ny), "double") for _ in range(2))
        S.snap_armed, S.snap_verbose = (array(np.zeros(snaps * n), "int") for _ in range(2))
        S.snap_side = array(np.zeros(snaps * n), "double")
        S.snap_senval = array(np.zeros(max(snaps * ns, 1)), "double")
        # where forces read SENVAL, a restart's consistent yp (ps_consistent_yp's workspace)
        S.consistent = int(bool(kernel.forces_use_senval))
        self.whole = whole_restart(kernel) if S.consistent and not dense_yp(kernel) else None
        if self.whole is not None:
            S.whole = self.whole.r
        elif S.consistent:
            ny = kernel.ny
            S.cwork = array(np.zeros(2 * ny * ny + ny), "double")
            S.cpiv = array(np.zeros(ny), "int")
        self._records(cap)
        self.reset()

    def tasks(self, controls):
        """Room to remember the run's LoadControl tasks (their ``psControl`` and their law's
        last loads) with each converged step, for a zero-crossing restore."""
        from ..build.bindings import ffi, lib
        S = self.S
        if not controls or not S.nzc:
            return
        self.snap_ctl = ffi.new("psControl[]", lib.PS_SNAPS * len(controls))
        S.snap_ctl = self.snap_ctl
        S.nloads = sum(task.c.law.window for task in controls)
        self.snap_loads = np.zeros(lib.PS_SNAPS * S.nloads)
        S.snap_loads = ffi.cast("double *", ffi.from_buffer(self.snap_loads))

    def _records(self, cap):
        """Room for `cap` records (events, and verbose sensors' log lines)."""
        from ..build.bindings import ffi
        self.ev = (np.zeros(cap), np.zeros(cap), np.zeros(cap, dtype=np.int32))
        S = self.S
        S.ev_time, S.ev_value = (ffi.cast("double *", ffi.from_buffer(a)) for a in self.ev[:2])
        S.ev_sensor = ffi.cast("int *", ffi.from_buffer(self.ev[2]))
        S.cap = cap

    def reserve(self, rows):
        """Room (the records drained) for an instant's events and a log line per verbose
        sensor for each of `rows` rows more."""
        S = self.S
        need = S.n + S.nverbose * (rows + 2)
        if need > S.cap - S.nev:
            self.drain()                      # the records so far, in order, first
            self._records(max(need, S.cap))

    def reset(self):
        """A new run: no events, re-armings, recent firings, searches or remembered steps;
        every sensor armed."""
        S = self.S
        S.nev = S.nrearms = S.first = S.nrecent = S.drained = S.nsnap = S.snap_first = 0
        S.saved, S.undo = 0, -1
        self.kernel.armed[:] = 1
        self.events, self.log = [], []
        self.kinds = []                 # per record handed over: an event (True) or a line

    def drain(self, upto=None):
        """Move the records made in C (the first `upto` of them; None: all) to :attr:`events`
        and :attr:`log`, after taking back those a restore undid."""
        S = self.S
        if S.undo >= 0:
            self.log, self.kinds = self.log[:S.undo], self.kinds[:S.undo]
            self.events = self.events[:sum(self.kinds)]
            S.drained, S.undo = len(self.kinds), -1
        t, value, sensor = self.ev
        n = len(self.sensors)
        count = S.nev if upto is None else upto
        for i in range(count):
            code = int(sensor[i])
            self.kinds.append(code >= 0)
            if code < -n:                        # a zero-crossing search began
                se = self.sensors[-1 - n - code]
                self.log.append(f"t = {t[i]:.9g}: Sensor_Event {se.id} zero crossing: back "
                                f"to the last converged step, hmax {value[i]:.3g}")
                continue
            if code < 0:                         # a verbose sensor's line at an output row
                se = self.sensors[-1 - code]
                self.log.append(f"t = {t[i]:.9g}: Sensor_Event {se.id} active (value "
                                f"{value[i]:.6g} {se.compare} {se.value:g})")
                continue
            se = self.sensors[code]
            actions = se.actions()
            self.events.append(Event(float(t[i]), se.id, se.label, float(value[i]), actions))
            self.log.append(f"t = {t[i]:.9g}: Sensor_Event {se.id} fired (value {value[i]:.6g} "
                            f"{se.compare} {se.value:g}): {', '.join(actions) or 'log only'}")
        S.drained += count
        S.nev = 0

    def halted_by(self):
        """The element that halted the run."""
        return f"Sensor_Event {self.sensors[self.S.halt].id}"

    def chatter(self):
        """The message of a run ended by chattering sensors (as :class:`Sensors` words it)."""
        S = self.S
        first, last = S.recent[S.first], S.recent[(S.first + S.nrecent - 1) % CHATTER_LIMIT]
        return (f"sensor events chatter: {CHATTER_LIMIT} events between t = {first:.12g} and "
                f"{last:.12g}; the sensors keep re-firing without time advancing (give them an "
                "error_tol band)")
