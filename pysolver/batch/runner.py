"""``pysolver.sweep``: many cases of one model, compiled once, on all cores or a Dask cluster.

The model is compiled once per worker; a case only changes numbers the kernel reads at run time
(:mod:`pysolver.build.params`). Cases run in worker processes (:mod:`.pool`), never in this
one unless ``processes=0``: nothing here compiles the model or runs a user subroutine. Each
finished case is written at once when a directory is given (:mod:`.store`), by this process,
so a sweep that is interrupted or killed loses nothing; running it again into the same
directory reuses the rows whose key (the deck, the files it names, pysolver's version, the
outputs and the case: :func:`.case.fingerprint`) is there with status ``ok`` (``keep=``
chooses), and runs the others.
"""
import math
import numbers
import os
import pickle
import sys
import time
import warnings

from ..options import TRANSIENT_ONLY
from .case import CaseRunner, case_key, check_outputs, fingerprint, reusable
from .pool import Pool, run_chunk
from .store import STATUSES, WITH_RESULT, StorageError, Store
from .table import Table

__all__ = ["STATUSES", "StorageError", "Sweep", "sweep"]

#: The table's own columns, around the inputs (before) and the outputs (after ``steps``).
BOOKKEEPING = ("case", "status", "message", "wall", "steps", "resumed")


class Sweep:
    """The outcome of :func:`sweep`.

    Attributes
    ----------
    rows : list of dict
        One per case, in case order: ``case`` (its index), its inputs (one key per path),
        ``status`` (ok, failed, error, crashed, timeout), ``message``, ``wall`` (seconds),
        ``steps``, and the outputs asked for; ``resumed`` is True for rows read from an earlier
        run into the same directory. Every row has the keys of :attr:`columns`, None where a
        case has no value (no steps and no outputs for a case that did not run).
    columns : list of str
        The table's columns, fixed by the sweep's design whatever the cases did: ``case``, the
        paths of the cases (in the order they first appear), ``status``, ``message``,
        ``wall``, ``steps``, the outputs in the order given, ``resumed``.
    """

    def __init__(self, model, cases, rows, columns, store, keys, payload, in_process):
        self.model, self.cases, self.rows, self.columns = model, cases, rows, columns
        self.directory, self.keys = store.directory, keys
        self._store, self._payload, self._in_process = store, payload, in_process
        self._results, self._runner = {}, None

    @property
    def table(self):
        """The rows as columns (:class:`pysolver.batch.table.Table`: name -> NumPy array,
        printable), without pandas; :meth:`to_dataframe` for a pandas DataFrame."""
        return Table(self.rows, self.columns)

    def to_dataframe(self):
        """The rows as a pandas DataFrame indexed by case (``pip install pandas``)."""
        return self.table.to_dataframe()

    def counts(self):
        """Number of cases per status."""
        return {s: sum(r["status"] == s for r in self.rows) for s in STATUSES}

    def result(self, i):
        """The full Result of case i: from the sweep's directory when it kept one (whole),
        else run again in a worker process (in this process after ``processes=0``; cases are
        deterministic: the same numbers). None for a case that did not run (error, crashed,
        timeout)."""
        if self.rows[i]["status"] not in WITH_RESULT:
            return None
        if i in self._results:
            return self._results[i]
        if self.directory:
            res = self._store.load(self.keys[i])
            if res is not None:
                return self._with_origin(res, i)
        if self._in_process:
            if self._runner is None:
                self._runner = CaseRunner(self.model)
            res = self._runner.run(self.cases[i], {})[1]
        else:
            got = list(Pool(self._payload, 1).run([(i, self.cases[i])], want=True))
            res = pickle.loads(got[0][2]) if got and got[0][2] is not None else None
        self._results[i] = res = self._with_origin(res, i)
        return res

    def _with_origin(self, res, i):
        """`res` knowing its model and case, for res.animate() (a Result leaves them behind
        when pickled)."""
        if res is not None:
            res._origin = (self.model, dict(self.cases[i]))
        return res

    def __repr__(self):
        c = self.counts()
        return f"<Sweep of {len(self.rows)} cases: " + ", ".join(
            f"{n} {s}" for s, n in c.items() if n) + ">"


def sweep(deck_or_model, cases, *, processes=None, client=None, timeout=None, outputs=None,
          directory=None, progress=None, keep=("ok",), startup_timeout=None):
    """Run every case of a model: one call for a whole parameter study.

    Parameters
    ----------
    deck_or_model : str, path, pysolver.Model, or pysolver.msolve.Model
        The deck, its loaded model, or a model of msolve classes (its ``load()``, with its
        simulate commands so far).
    cases : list of dict, pandas.DataFrame, or a design (:func:`pysolver.grid`,
        :func:`pysolver.sample`)
        Each case maps paths (``"Force_Penalty/1/penalty"``; see
        :class:`pysolver.build.params.Parameters`) to numbers, checked by the rules the
        deck's own attribute has.
    processes : int, optional
        Worker processes (default: one per core); 0 runs the cases in this process (no crash
        isolation, no time limit).
    client : dask.distributed.Client, optional
        Run the cases as tasks on this Dask cluster instead; each Dask worker runs them in a
        worker process of its own, so crashes and ``timeout`` are handled as here.
    timeout : float, optional
        Seconds a case may run before its worker is killed (status ``timeout``), counted from
        when the worker has loaded and compiled the model.
    outputs : dict, optional
        Name -> scalar to record per case: ``"final:request/1/2"``, ``"max:body2.z"``,
        ``"first_event"``, ``"steps"``, or a function of the Result (sent to the workers by
        cloudpickle when it is installed, else by reference: define it in a module).
    directory : str, optional
        Write rows and Results there as cases finish, and reuse the rows already there.
    progress : bool, optional
        A progress bar on standard error (default: when it is a terminal).
    keep : str or sequence of str, default ("ok",)
        Statuses of stored rows to reuse; the other stored cases run again (a ``timeout``
        with a longer limit, say). ``"all"`` reuses every stored row.
    startup_timeout : float, optional
        Seconds a worker may take to load and compile the model before the case it holds is
        ``timeout`` (default: with a `timeout`, the larger of it and 300 s, the time a large
        deck's generated C may take; without one, no limit). Two workers in a row that run
        out of it make the cases not yet run ``timeout`` rows at once.

    Returns
    -------
    Sweep

    Raises
    ------
    StorageError
        The directory cannot be written (read-only, a full disk, ``results`` a file): the
        sweep stops, the cases stored so far are kept.
    KeyboardInterrupt
        Ctrl-C: the sweep stops; the cases running then are not stored.
    """
    model = _model(deck_or_model)
    cases = _as_cases(cases)
    outputs = dict(outputs or {})
    check_outputs(model, outputs)
    columns = _columns(cases, outputs)
    _warn_transient_only(model, columns)
    keep = _keep(keep)
    startup_timeout = _seconds("startup_timeout", startup_timeout)
    fp = fingerprint(model, outputs)
    keys = [case_key(fp, c) for c in cases]
    in_process = processes == 0 and client is None
    payload = None if in_process else (fp, _blob(model, outputs), reusable(model))
    store = Store(directory)
    rows = [None] * len(cases)
    for i, key in enumerate(keys):
        got = store.stored(key, keep)
        if got is not None:
            rows[i] = _row(columns, i, cases[i], got, True)
    todo = [(i, cases[i]) for i in range(len(cases)) if rows[i] is None]
    bar = _Bar(len(cases), len(cases) - len(todo), progress)
    want = store.directory is not None
    if client is not None:
        finished = _dask(client, payload, todo, timeout, want, startup_timeout)
    elif in_process:
        finished = _serial(model, todo, outputs, want)
    else:
        finished = Pool(payload, processes or os.cpu_count() or 1, timeout,
                        startup_timeout).run(todo, want)
    try:
        for idx, row, blob in finished:
            row = _row(columns, idx, cases[idx], row, False)
            store.add(keys[idx], row, blob)
            rows[idx] = row
            bar.step()
    finally:
        finished.close()                # workers of an unfinished sweep are stopped now
        store.close()
        bar.close()
    return Sweep(model, cases, rows, columns, store, keys, payload, in_process)


def _model(deck_or_model):
    """The pysolver.Model a sweep runs: loaded from a deck path, or an msolve Model's."""
    from ..deck.loader import load
    from ..model import Model
    from ..modeling import Model as ClassModel
    if isinstance(deck_or_model, Model):
        return deck_or_model
    if isinstance(deck_or_model, ClassModel):
        return deck_or_model.load()
    if not isinstance(deck_or_model, (str, bytes, os.PathLike)):
        raise TypeError(f"sweep takes a deck path, a pysolver.Model or an msolve Model, not "
                        f"{type(deck_or_model).__name__}")
    return load(deck_or_model)


def _columns(cases, outputs):
    """The table's columns: ``case``, every path of the cases, the bookkeeping, the outputs
    (an output ``steps`` is the bookkeeping column of that name), ``resumed``. An output
    named as another column is refused: it would hide that column."""
    paths = _paths(cases)
    for name, spec in outputs.items():
        if name in paths or (name in BOOKKEEPING and (name, spec) != ("steps", "steps")):
            raise ValueError(f"output {name!r}: the table has a column {name!r} already (case, "
                             "the paths of the cases, status, message, wall, steps, resumed); "
                             "choose another name")
    return list(dict.fromkeys(["case", *paths, "status", "message", "wall", "steps",
                               *outputs, "resumed"]))


def _paths(cases):
    """Every path of the cases, in the order they first appear; a ValueError for a path a
    case gives twice (paths are case-insensitive: two spellings are one number) or that the
    cases spell two ways (two columns for one number)."""
    spelled = {}                        # lower-case path -> its spelling in the cases
    for i, case in enumerate(cases):
        seen = {}
        for key in map(str, case):
            low = key.lower()
            if low in seen:
                raise ValueError(f"case {i} gives one path twice, as {seen[low]!r} and {key!r} "
                                 "(paths are case-insensitive)")
            seen[low] = key
            first = spelled.setdefault(low, key)
            if first != key:
                raise ValueError(f"the cases spell one path two ways, {first!r} and {key!r} "
                                 f"(case {i}); paths are case-insensitive: use one spelling")
    return list(spelled.values())


def _warn_transient_only(model, paths):
    """A warning for Param_Transient paths a deck without a transient command does not use
    (its static and quasi-static commands take integr_tol alone): they would vary nothing."""
    analyses = {c.analysis for c in model.commands}
    if "TRANSIENT" in analyses or not analyses & {"STATIC", "QUASI-STATIC"}:
        return
    unused = [p for p in paths if p.lower().startswith("param_transient/")
              and p.split("/")[-1].lower() in TRANSIENT_ONLY]
    if unused:
        warnings.warn(f"{', '.join(unused)}: the deck has no transient command, and its static "
                      "and quasi-static commands take integr_tol alone (docs/statics.md): these "
                      "values change nothing", UserWarning, stacklevel=3)


def _row(columns, idx, case, got, resumed):
    """A row with every column: the case's inputs, the bookkeeping and outputs it got (None
    for those it has not: a case that did not run has no steps and no outputs)."""
    row = dict.fromkeys(columns)
    inputs = {str(k): v for k, v in case.items()}
    row.update(inputs)
    row.update((k, v) for k, v in got.items()
               if k in row and (k not in inputs or k in BOOKKEEPING))
    row["case"], row["resumed"] = idx, resumed
    return row


def _seconds(name, value):
    """A time limit: None, or a finite number of seconds > 0 (else a ValueError naming it)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or \
            not math.isfinite(value) or value <= 0:
        raise ValueError(f"{name}: got {value!r}; expected a number of seconds > 0")
    return float(value)


def _keep(keep):
    keep = STATUSES if keep == "all" else (keep,) if isinstance(keep, str) else tuple(keep)
    bad = [k for k in keep if k not in STATUSES]
    if bad:
        raise ValueError(f"keep: unknown status {bad[0]!r}; expected 'all' or some of "
                         f"{', '.join(STATUSES)}")
    return keep


def _blob(model, outputs):
    """(model, outputs) as a worker loads them: the model as its deck text; functions among
    the outputs by value with cloudpickle, else by reference."""
    if any(callable(s) for s in outputs.values()):
        try:
            import cloudpickle
        except ImportError:
            for name, spec in outputs.items():
                if callable(spec) and getattr(spec, "__module__", None) == "__main__":
                    raise ValueError(f"output {name!r}: a function of the main script cannot "
                                     "reach the worker processes; define it in a module, or "
                                     "pip install cloudpickle") from None
        else:
            return cloudpickle.dumps((model, outputs), protocol=pickle.HIGHEST_PROTOCOL)
    try:
        return pickle.dumps((model, outputs), protocol=pickle.HIGHEST_PROTOCOL)
    except (pickle.PicklingError, AttributeError, TypeError) as err:
        raise ValueError(f"outputs: cannot send them to the worker processes ({err}); use "
                         "spec strings or module-level functions") from None


def _as_cases(cases):
    if hasattr(cases, "to_dict") and hasattr(cases, "columns"):      # a DataFrame
        return [dict(r) for r in cases.to_dict(orient="records")]
    return [dict(c) for c in cases]


def _serial(model, todo, outputs, want):
    runner = CaseRunner(model)
    for idx, case in todo:
        row, res = runner.run(case, outputs)
        if row["status"] == "interrupted":
            raise KeyboardInterrupt(f"case {idx}: {row['message']}")
        blob = pickle.dumps(res, protocol=pickle.HIGHEST_PROTOCOL) \
            if want and res is not None else None
        yield idx, row, blob


def _dask(client, payload, todo, timeout, want, startup=None):
    """Cases as Dask tasks, a few dozen per task (a task costs the scheduler about a
    millisecond), each run by a worker process of the Dask worker (:func:`.pool.run_chunk`:
    a crashing case is its row ``crashed``, the Dask worker lives on). A task that fails
    anyway (a Dask worker lost) runs again case by case."""
    from dask.distributed import as_completed
    nworkers = max(1, len(client.scheduler_info().get("workers", {})))
    size = max(1, min(50, len(todo) // (8 * nworkers)))
    chunks = [todo[i:i + size] for i in range(0, len(todo), size)]
    futures = {client.submit(run_chunk, payload, chunk, timeout, want, startup, pure=False):
               chunk for chunk in chunks}
    try:
        for fut in as_completed(futures):
            chunk = futures[fut]
            try:
                got = fut.result()
            except Exception as err:  # noqa: BLE001 - a Dask worker lost or the task failed
                if len(chunk) == 1:
                    kind = "crashed" if type(err).__name__ == "KilledWorker" else "error"
                    yield chunk[0][0], {"status": kind,
                                        "message": f"{type(err).__name__}: {err}",
                                        "wall": math.nan, "steps": None}, None
                else:
                    yield from _dask(client, payload, chunk, timeout, want, startup)
                continue
            yield from got
    finally:
        client.cancel([f for f in futures if not f.done()])


class _Bar:
    """Cases done, on one line of standard error."""

    def __init__(self, total, done, enabled):
        self.total, self.done = total, done
        self.enabled = sys.stderr.isatty() if enabled is None else enabled
        self.t0 = time.perf_counter()

    def step(self):
        self.done += 1
        if self.enabled:
            frac = self.done / max(self.total, 1)
            sys.stderr.write(f"\r  [{'#' * int(30 * frac):<30}] {self.done}/{self.total} cases "
                             f"({time.perf_counter() - self.t0:.1f} s)")
            sys.stderr.flush()

    def close(self):
        if self.enabled:
            sys.stderr.write("\n")
