"""The :class:`~pysolver.Result` of a run, whichever path ran it (:mod:`.fast` or the driver,
:mod:`.driver`): its statistics, timing and metadata are built here, once.

What the Results of one model's runs under one plan and settings share (metadata, units, the
request channels' columns) is a :class:`Reporter`, built once: the batched path keeps one for
all its runs, so a short run's Result costs a few microseconds of Python.
"""
from .._version import __version__
from ..deck.dimensions import channel_units
from ..results import Result
from . import kept, nonfinite, precision


class Reporter:
    """Builds the Results of runs of `model` on `kernel` under `plan` and `settings`.

    Parameters
    ----------
    model, kernel, plan
        What runs and how (:class:`~.integrator.Plan`).
    settings : tuple
        (options as a dict, Param_Static as a dict, request labels) of solve.run._settings.
    """

    def __init__(self, model, kernel, plan, settings):
        used, static, labels = settings
        self.model, self.kernel, self.plan, self.labels = model, kernel, plan, labels
        self.used = dict(used, linsolver=plan.linsolver,
                         backend="c" if plan.use_c else "sksundae")
        self.static = dict(static)
        self.commands = [(c.analysis, c.end_time) for c in model.commands]
        self.units = channel_units(model)
        self.column_map = column_map(kernel.channels)
        self.names = list(kernel.layout.names)
        # the labels res.request / joint / motion / controller take for ids
        self.element_labels = {
            kind: {el.id: el.label for el in getattr(model, table).values() if el.label}
            for kind, table in (("request", "requests"), ("joint", "joints"),
                                ("motion", "motions"), ("controller", "controls"))}

    def result(self, rows, outcome, clock, ida, log, *, steps, nevents=0, nrearms=0,
               nrestarts=0, onestep=False, events=(), statics=(), controllers=None):
        """Build the Result of a run.

        Parameters
        ----------
        rows : tuple
            (t, y, yp, outputs) arrays.
        outcome : tuple
            (success, status, message).
        clock : tuple
            perf_counter times of the start, the end of the set-up (initial conditions) and
            the end.
        ida : dict
            IDA's counters (integrator interface) with ``growth_limited_at``.
        log : list of str
            The run's log; lines for non-finite request channels are added.
        steps, nevents, nrearms, nrestarts : int
        onestep : bool
            Whether the run stepped one internal step at a time (restore-and-shrink).
        events, statics, controllers
            What the driver's actors recorded.
        """
        model, kernel, plan = self.model, self.kernel, self.plan
        t, y, yp, outputs = rows
        success, status, message = outcome
        if success and len(t):
            why = kept.check(model, kernel, t, y, self.used["integr_tol"])
            if why:
                success, status, message = False, kept.STATUS, why
        if success and len(t):
            why = precision.check(model, kernel, t, y, yp)
            if why:
                success, status, message = False, precision.STATUS, why
        t_start, t_setup, t_end = clock
        d, gen = kernel.d, kernel.codegen
        stats = {"steps": steps, "nres": int(d.nres), "njac": int(d.njac),
                 "nfail": int(d.nfail), "outputs": len(t), "nroots": int(d.nroots),
                 "nevents": nevents, "nrearms": nrearms, "nrestarts": nrestarts,
                 "ida_nfev": ida["nfev"], "ida_njev": ida["njev"],
                 "netf": ida["netf"] if plan.use_c else None,
                 "ncfn": ida["ncfn"] if plan.use_c else None,
                 "growth_limited_at": ida["growth_limited_at"]}
        timing = {"setup": t_setup - t_start, "integrate": t_end - t_setup,
                  "total": t_end - t_start,
                  # the one-time cost of the generated kernel, on the run that built it
                  "generate": gen.pop("generate_unreported", 0.0),
                  "compile": gen.pop("compile_unreported", 0.0)}
        # every Result has metadata of its own (a caller may change one)
        meta = {"version": __version__, "deck": model.source.file,
                "sha256": model.source.sha256, "options": dict(self.used), "ny": kernel.ny,
                "stepping": "onestep" if onestep else "normal", "static": dict(self.static),
                "usersubs": dict(model.usersub_paths), "kernel": gen["kernel"],
                # each Simulate command's analysis and end time (plots mark the boundaries)
                "commands": [{"analysis": a, "end_time": e} for a, e in self.commands]}
        # the kernel noted whether any row's defined channel was not finite (ps_outputs)
        log = list(log) + getattr(kernel, "start_notes", []) + (
            nonfinite.channels(model, kernel, t, outputs) if kernel.d.out_nonfinite else [])
        return Result(t=t, y=y, yp=yp, outputs=outputs, channels=kernel.channels,
                      state_names=self.names, success=success, status=status,
                      message=message, stats=stats, timing=timing, meta=meta,
                      labels=self.labels, events=events, log=log, statics=statics,
                      controllers=controllers, units=self.units,
                      column_map=self.column_map, element_labels=self.element_labels)


def column_map(channels):
    """({(request id, channel index): column}, the request ids, sorted) of a kernel's request
    `channels` (a negative id is a joint's reactions)."""
    column = {tuple(ch): col for col, ch in enumerate(channels)}
    return column, sorted({rid for rid, _ in column if rid > 0})


def result(model, kernel, plan, settings, rows, outcome, clock, ida, log, **recorded):
    """The Result of one run (:meth:`Reporter.result` of a Reporter built for it)."""
    return Reporter(model, kernel, plan, settings).result(rows, outcome, clock, ida, log,
                                                          **recorded)
