"""The :class:`~pysolver.Result` of a run, whichever path ran it (:mod:`.fast` or the driver,
:mod:`.driver`): its statistics, timing and metadata are built here, once."""
from .._version import __version__
from ..deck.dimensions import channel_units
from ..results import Result
from . import nonfinite, precision


def result(model, kernel, plan, settings, rows, outcome, clock, ida, log, *, steps,
           nevents=0, nrearms=0, nrestarts=0, onestep=False, events=(), statics=(),
           controllers=None):
    """Build the Result of a run.

    Parameters
    ----------
    model, kernel, plan
        What ran and how (:class:`~.integrator.Plan`).
    settings : tuple
        (options as a dict, Param_Static as a dict, request labels) of solve.run._settings.
    rows : tuple
        (t, y, yp, outputs) arrays.
    outcome : tuple
        (success, status, message).
    clock : tuple
        perf_counter times of the start, the end of the set-up (initial conditions) and the
        end.
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
    used, static, labels = settings
    t, y, yp, outputs = rows
    success, status, message = outcome
    if success and len(t):
        why = precision.check(model, kernel, t[-1], y[-1], yp[-1])
        if why:
            success, status, message = False, precision.STATUS, why
    t_start, t_setup, t_end = clock
    c, gen = kernel.counters, kernel.codegen
    stats = {"steps": steps, "nres": c["nres"], "njac": c["njac"], "nfail": c["nfail"],
             "outputs": len(t), "nroots": c["nroots"], "nevents": nevents, "nrearms": nrearms,
             "nrestarts": nrestarts, "ida_nfev": ida["nfev"], "ida_njev": ida["njev"],
             "netf": ida["netf"] if plan.use_c else None,
             "ncfn": ida["ncfn"] if plan.use_c else None,
             "growth_limited_at": ida["growth_limited_at"]}
    timing = {"setup": t_setup - t_start, "integrate": t_end - t_setup,
              "total": t_end - t_start,
              # the one-time cost of the generated kernel, on the run that built it
              "generate": gen.pop("generate_unreported", 0.0),
              "compile": gen.pop("compile_unreported", 0.0)}
    used = dict(used, linsolver=plan.linsolver, backend="c" if plan.use_c else "sksundae")
    meta = {"version": __version__, "deck": model.source.file, "sha256": model.source.sha256,
            "options": used, "ny": kernel.ny, "stepping": "onestep" if onestep else "normal",
            "static": dict(static), "usersubs": dict(model.usersub_paths),
            "kernel": gen["kernel"],
            # each Simulate command's analysis and end time (plots mark the boundaries)
            "commands": [{"analysis": c.analysis, "end_time": c.end_time}
                         for c in model.commands]}
    log = list(log) + nonfinite.channels(model, kernel, t, outputs)
    return Result(t=t, y=y, yp=yp, outputs=outputs, channels=kernel.channels,
                  state_names=kernel.layout.names, success=success, status=status,
                  message=message, stats=stats, timing=timing, meta=meta, labels=labels,
                  events=events, log=log, statics=statics, controllers=controllers,
                  units=channel_units(model))
