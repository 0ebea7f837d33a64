"""``Model.run``: options, the fast path (:mod:`.fast`) or one :class:`~.driver.Run`, and the
:class:`~pysolver.Result`."""
import dataclasses
import threading
import time

from ..build.bindings import lib
from ..deck.dimensions import channel_units
from . import integrator, quasistatic, report
from .driver import Run
from .fast import fast_run
from .outputs import Stream


def run_model(compiled, progress=None, overrides=None, actors=(), stream=None):
    """Run every command of a compiled model (or of a Model: its default compilation, or the
    one the ``kernel`` override asks for); see :meth:`pysolver.Model.run`.

    `overrides` maps option names to values for this run (see Options). `actors` are further
    :class:`~.actors.Actor` objects that act at their own times (tools and tests; the deck's own
    actors, such as its sensors, are always there). `stream`, a path, gets the rows as CSV as
    they are made (:class:`~.outputs.Stream`).
    """
    t_start = time.perf_counter()
    if not hasattr(compiled, "kernel"):          # a Model
        compiled = compiled.compile((overrides or {}).get("kernel"))
    kernel = compiled.kernel
    options, used, static, labels = _settings(compiled, overrides)
    kind = compiled.kind
    gen = kernel.codegen
    log = [f"kernel: the tapes run ({gen['why']})"] if gen["kernel"] == "tapes" and \
        kind != "tapes" else []
    log += compiled.notes
    unused = quasistatic.unused_note(compiled.model, options)
    if unused:
        log.append(unused)
    fim_d = quasistatic.fim_d_note(compiled.model)
    if fim_d:
        log.append(fim_d)
    if getattr(compiled.model, "default_command", False):
        log.append("no Simulate command: the default run, a transient of 1 s with 100 "
                   "outputs (docs/deck-language.md)")
    sink = Stream(stream, kernel, labels, channel_units(compiled.model)) \
        if stream is not None else None
    # Ctrl-C ends a run at its next residual (the C kernel's handler; main thread only)
    main = threading.current_thread() is threading.main_thread()
    if main:
        lib.ps_interrupt_arm()
    try:
        fast = fast_run(compiled, options, actors)
        if fast is not None:
            res = fast.run(t_start, used, static, labels, log, progress, sink)
            if res is not None:
                return res
        return _driver_run(compiled, options, progress, actors, sink, t_start,
                           (used, static, labels), log)
    finally:
        if main:
            lib.ps_interrupt_disarm()
        if sink is not None:
            sink.close()


def _driver_run(compiled, options, progress, actors, sink, t_start, settings, log):
    model, kernel = compiled.model, compiled.kernel
    kernel.reset_counters()
    run = Run(model, kernel, options, integrator.cached_plan(compiled, options), progress,
              sink)
    run.log.extend(log)
    for actor in actors:
        run.add_actor(actor)
    success, status, message = run.run()
    t_end = time.perf_counter()
    ida, growth_limited_at = run.counters()
    ida["growth_limited_at"] = growth_limited_at
    pr = run.printer
    rows = (pr.ts.array(), pr.ys.array(kernel.ny), pr.yps.array(kernel.ny),
            pr.outs.array(len(kernel.channels)))
    return report.result(model, kernel, run.plan, settings, rows,
                         (success, status, message), (t_start, run.t_setup or t_end, t_end),
                         ida, run.log, steps=run.steps(), nevents=len(run.events),
                         nrearms=run.sensors.nrearms, nrestarts=max(run.nstarts - 1, 0),
                         onestep=run.onestep, events=run.events, statics=run.statics,
                         controllers={task.lc.id: task.records() for task in run.controls})


def _settings(compiled, overrides):
    """(options, options as a dict, Param_Static as a dict, request labels) of a run, kept on
    the compiled model for the next run with the same deck settings and overrides
    (dataclasses.asdict alone cost about a third of a short run's Python)."""
    model = compiled.model
    items = tuple(sorted((overrides or {}).items()))
    key = (id(model.transient), id(model.static), items)
    cached = compiled.run_settings
    try:
        if cached is not None and cached[0] == key:
            return cached[3:]
    except (TypeError, ValueError):     # an override that does not compare (an array)
        pass
    options = model.transient.replace(**dict(items))
    labels = {(r.id, k): n for r in model.requests.values() for k, n in enumerate(r.names) if n}
    # the key's objects are kept alive with it, so their ids are not reused
    compiled.run_settings = (key, model.transient, model.static, options,
                             dataclasses.asdict(options), dataclasses.asdict(model.static),
                             labels)
    return compiled.run_settings[3:]
