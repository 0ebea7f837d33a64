"""``Model.run``: options, one :class:`~.driver.Run`, and the :class:`~pysolver.Result`."""
import dataclasses
import threading
import time

from .._version import __version__
from ..build.bindings import lib
from ..results import Result
from . import nonfinite
from .driver import Run


def run_model(model, progress=None, overrides=None, actors=()):
    """Run every command of `model`; see :meth:`pysolver.Model.run`.

    `overrides` maps option names to values for this run (see Options). `actors` are further
    :class:`~.actors.Actor` objects that act at their own times (tools and tests; the deck's own
    actors, such as its sensors, are always there).
    """
    t_start = time.perf_counter()
    options = model.transient.replace(**(overrides or {}))
    kernel = model._kernel()
    kernel.reset_counters()
    run = Run(model, kernel, options, progress)
    for actor in actors:
        run.add_actor(actor)
    t_run = time.perf_counter()
    # Ctrl-C (main thread only): the C kernel's handler ends the run at its next residual
    main = threading.current_thread() is threading.main_thread()
    if main:
        lib.ps_interrupt_arm()
    try:
        success, status, message = run.run()
    finally:
        if main:
            lib.ps_interrupt_disarm()
    t_end = time.perf_counter()
    ida, growth_limited_at = run.counters()
    c = kernel.counters
    stats = {"steps": run.steps(), "nres": c["nres"], "njac": c["njac"], "nfail": c["nfail"],
             "outputs": len(run.printer.ts), "nroots": c["nroots"],
             "nevents": len(run.events), "nrearms": run.sensors.nrearms,
             "nrestarts": max(run.nstarts - 1, 0),
             "ida_nfev": ida["nfev"], "ida_njev": ida["njev"],
             "netf": ida["netf"] if run.plan.use_c else None,
             "ncfn": ida["ncfn"] if run.plan.use_c else None,
             "growth_limited_at": growth_limited_at}
    setup = (t_run - t_start) + ((run.t_setup or t_end) - t_run)
    timing = {"setup": setup, "integrate": (t_end - t_start) - setup, "total": t_end - t_start}
    used = dataclasses.asdict(options)
    used.update(linsolver=run.plan.linsolver, backend="c" if run.plan.use_c else "sksundae")
    meta = {"version": __version__, "deck": model.source.file, "sha256": model.source.sha256,
            "options": used, "ny": kernel.ny, "stepping": "onestep" if run.onestep else "normal",
            "static": dataclasses.asdict(model.static),
            "usersubs": dict(model.usersub_paths)}
    labels = {(r.id, k): n for r in model.requests.values() for k, n in enumerate(r.names) if n}
    pr = run.printer
    ts, outputs = pr.ts.array(), pr.outs.array(len(kernel.channels))
    run.log.extend(nonfinite.channels(model, kernel.channels, ts, outputs))
    return Result(t=ts, y=pr.ys.array(kernel.ny), yp=pr.yps.array(kernel.ny),
                  outputs=outputs, channels=kernel.channels,
                  state_names=kernel.layout.names, success=success, status=status,
                  message=message, stats=stats, timing=timing, meta=meta, labels=labels,
                  events=run.events, log=run.log, statics=run.statics,
                  controllers={task.lc.id: task.records() for task in run.controls})
