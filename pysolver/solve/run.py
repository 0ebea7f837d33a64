"""``Model.run``: options, the fast path (:mod:`.fast`) or one :class:`~.driver.Run`, and the
:class:`~pysolver.Result`."""
import dataclasses
import threading
import time

from .._version import __version__
from ..build.bindings import lib
from ..results import Result
from . import nonfinite
from .driver import Run
from .fast import fast_run


def run_model(model, progress=None, overrides=None, actors=()):
    """Run every command of `model`; see :meth:`pysolver.Model.run`.

    `overrides` maps option names to values for this run (see Options). `actors` are further
    :class:`~.actors.Actor` objects that act at their own times (tools and tests; the deck's own
    actors, such as its sensors, are always there).
    """
    t_start = time.perf_counter()
    options, used, static, labels = _settings(model, overrides)
    kind = options.resolved_kernel()
    kernel = model._kernel(kind=kind)
    gen = kernel.codegen
    log = [f"kernel: the tapes run ({gen['why']})"] if gen["kernel"] == "tapes" and \
        kind != "tapes" else []
    fast = fast_run(model, kernel, options, actors)
    if fast is not None:
        res = fast.run(t_start, used, static, labels, log, progress)
        if res is not None:
            return res
    kernel.reset_counters()
    run = Run(model, kernel, options, progress)
    run.log.extend(log)
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
    timing = {"setup": setup, "integrate": (t_end - t_start) - setup, "total": t_end - t_start,
              # the one-time cost of the generated kernel, on the run that built it
              "generate": gen.pop("generate_unreported", 0.0),
              "compile": gen.pop("compile_unreported", 0.0)}
    used = dict(used, linsolver=run.plan.linsolver,
                backend="c" if run.plan.use_c else "sksundae")
    meta = {"version": __version__, "deck": model.source.file, "sha256": model.source.sha256,
            "options": used, "ny": kernel.ny, "stepping": "onestep" if run.onestep else "normal",
            "static": dict(static), "usersubs": dict(model.usersub_paths),
            "kernel": gen["kernel"]}
    pr = run.printer
    ts, outputs = pr.ts.array(), pr.outs.array(len(kernel.channels))
    run.log.extend(nonfinite.channels(model, kernel, ts, outputs))
    return Result(t=ts, y=pr.ys.array(kernel.ny), yp=pr.yps.array(kernel.ny),
                  outputs=outputs, channels=kernel.channels,
                  state_names=kernel.layout.names, success=success, status=status,
                  message=message, stats=stats, timing=timing, meta=meta, labels=labels,
                  events=run.events, log=run.log, statics=run.statics,
                  controllers={task.lc.id: task.records() for task in run.controls})


def _settings(model, overrides):
    """(options, options as a dict, Param_Static as a dict, request labels) of a run, kept on
    the model for the next run with the same deck settings and overrides (dataclasses.asdict
    alone cost about a third of a short run's Python)."""
    items = tuple(sorted((overrides or {}).items()))
    key = (id(model.transient), id(model.static), items)
    cached = getattr(model, "_run_settings", None)
    try:
        if cached is not None and cached[0] == key:
            return cached[3:]
    except (TypeError, ValueError):     # an override that does not compare (an array)
        pass
    options = model.transient.replace(**dict(items))
    labels = {(r.id, k): n for r in model.requests.values() for k, n in enumerate(r.names) if n}
    # the key's objects are kept alive with it, so their ids are not reused
    model._run_settings = (key, model.transient, model.static, options,
                           dataclasses.asdict(options), dataclasses.asdict(model.static), labels)
    return model._run_settings[3:]
