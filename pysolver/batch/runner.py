"""``pysolver.sweep``: many cases of one model, compiled once, on all cores or a Dask cluster.

The model is compiled once per worker; a case only changes numbers the kernel reads at run time
(:mod:`pysolver.build.params`). Each finished case is written at once when a directory is
given (a line of ``cases.jsonl`` and its Result as ``results/<key>.pkl``), so a sweep that is
interrupted or killed loses nothing, and running it again into the same directory skips the
cases whose key (a hash of deck and case) is already there.
"""
import json
import math
import os
import pickle
import sys
import time

from .case import CaseRunner, case_key, check_outputs
from .pool import Pool, save_result

STATUSES = ("ok", "failed", "error", "crashed", "timeout")


class Sweep:
    """The outcome of :func:`sweep`.

    Attributes
    ----------
    rows : list of dict
        One per case, in case order: ``case`` (its index), its inputs (one key per path),
        ``status`` (ok, failed, error, crashed, timeout), ``message``, ``wall`` (seconds),
        ``steps``, and the outputs asked for; ``resumed`` is True for rows read from an earlier
        run into the same directory.
    """

    def __init__(self, model, cases, rows, directory, keys):
        self.model, self.cases, self.rows = model, cases, rows
        self.directory, self.keys = directory, keys
        self._results = {}

    @property
    def table(self):
        """The rows as a pandas DataFrame (``pip install pandas``)."""
        import pandas as pd
        return pd.DataFrame(self.rows).set_index("case")

    def counts(self):
        """Number of cases per status."""
        return {s: sum(r["status"] == s for r in self.rows) for s in STATUSES}

    def result(self, i):
        """The full Result of case i: from the sweep's directory when it kept one, else run
        again here (cases are deterministic: the same numbers). None for a case that did not
        run (error, crashed, timeout)."""
        if self.rows[i]["status"] not in ("ok", "failed"):
            return None
        if self.directory:
            path = os.path.join(self.directory, "results", f"{self.keys[i]}.pkl")
            if os.path.exists(path):
                with open(path, "rb") as fh:
                    return pickle.load(fh)
        if i not in self._results:
            self._results[i] = CaseRunner(self.model).run(self.cases[i], {})[1]
        return self._results[i]

    def __repr__(self):
        c = self.counts()
        return f"<Sweep of {len(self.rows)} cases: " + ", ".join(
            f"{n} {s}" for s, n in c.items() if n) + ">"


def sweep(deck_or_model, cases, *, processes=None, client=None, timeout=None, outputs=None,
          directory=None, progress=None):
    """Run every case of a model: one call for a whole parameter study.

    Parameters
    ----------
    deck_or_model : str, path or pysolver.Model
    cases : list of dict, pandas.DataFrame, or a design (:func:`pysolver.grid`,
        :func:`pysolver.sample`)
        Each case maps paths (``"Force_Penalty/1/penalty"``; see
        :class:`pysolver.build.params.Parameters`) to numbers.
    processes : int, optional
        Worker processes (default: one per core); 0 runs the cases in this process (no crash
        isolation, no time limit).
    client : dask.distributed.Client, optional
        Run the cases as tasks on this Dask cluster instead (the model travels once to each
        worker); ``timeout`` is not enforced there.
    timeout : float, optional
        Seconds a case may run before its worker is killed (status ``timeout``).
    outputs : dict, optional
        Name -> scalar to record per case: ``"final:request/1/2"``, ``"max:body2.z"``,
        ``"first_event"``, ``"steps"``, or a picklable function of the Result.
    directory : str, optional
        Write rows and Results there as cases finish, and skip cases already there.
    progress : bool, optional
        A progress bar on standard error (default: when it is a terminal).

    Returns
    -------
    Sweep
    """
    from .. import Model, load
    model = deck_or_model if isinstance(deck_or_model, Model) else load(deck_or_model)
    cases = _as_cases(cases)
    outputs = dict(outputs or {})
    check_outputs(model, outputs)
    keys = [case_key(model, c) for c in cases]
    rows = [None] * len(cases)
    store = _Store(directory)
    for i, key in enumerate(keys):
        if key in store.done:
            rows[i] = dict(store.done[key], case=i, resumed=True)
    todo = [(i, cases[i], store.path(keys[i])) for i in range(len(cases)) if rows[i] is None]
    bar = _Bar(len(cases), len(cases) - len(todo), progress)
    if client is not None:
        finished = _dask(client, model, todo, outputs)
    elif processes == 0:
        finished = _serial(model, todo, outputs)
    else:
        finished = Pool(model, processes or os.cpu_count() or 1, timeout).run(todo, outputs)
    for idx, row in finished:
        row = {"case": idx, **{str(k): v for k, v in cases[idx].items()}, **row,
               "resumed": False}
        rows[idx] = row
        store.add(keys[idx], row)
        bar.step()
    bar.close()
    return Sweep(model, cases, rows, directory, keys)


def _as_cases(cases):
    if hasattr(cases, "to_dict") and hasattr(cases, "columns"):      # a DataFrame
        return [dict(r) for r in cases.to_dict(orient="records")]
    out = [dict(c) for c in cases]
    return out


def _serial(model, todo, outputs):
    runner = CaseRunner(model)
    for idx, case, store in todo:
        row, res = runner.run(case, outputs)
        if store and res is not None:
            save_result(res, store)
        yield idx, row


def _dask(client, model, todo, outputs):
    """Cases as Dask tasks, a few dozen per task (a task costs the scheduler about a
    millisecond); a task that fails (a worker lost) runs again case by case, so that only the
    case that kills a worker is marked crashed."""
    from dask.distributed import as_completed
    remote = client.scatter(model, broadcast=True)
    nworkers = max(1, len(client.scheduler_info().get("workers", {})))
    size = max(1, min(50, len(todo) // (8 * nworkers)))
    chunks = [todo[i:i + size] for i in range(0, len(todo), size)]
    futures = {client.submit(_dask_cases, remote, chunk, outputs, pure=False): chunk
               for chunk in chunks}
    for fut in as_completed(futures):
        chunk = futures[fut]
        try:
            yield from fut.result()
            continue
        except Exception as err:  # noqa: BLE001 - a worker lost or the task failed there
            if len(chunk) == 1:
                kind = "crashed" if type(err).__name__ == "KilledWorker" else "error"
                yield chunk[0][0], {"status": kind, "message": f"{type(err).__name__}: {err}",
                                    "wall": math.nan, "steps": None}
                continue
        yield from _dask(client, model, chunk, outputs)      # smaller chunks, down to one


_RUNNERS = {}


def _dask_cases(model, chunk, outputs):
    """Cases on a Dask worker, with one compiled model per worker and deck."""
    runner = _RUNNERS.get(model.source.sha256)
    if runner is None:
        runner = _RUNNERS[model.source.sha256] = CaseRunner(model)
    out = []
    for idx, case, store in chunk:
        row, res = runner.run(case, outputs)
        if store and res is not None:
            save_result(res, store)
        out.append((idx, row))
    return out


class _Store:
    """A sweep's directory: rows in cases.jsonl, Results in results/."""

    def __init__(self, directory):
        self.directory = directory
        self.done = {}
        if not directory:
            return
        os.makedirs(os.path.join(directory, "results"), exist_ok=True)
        self.file = os.path.join(directory, "cases.jsonl")
        if os.path.exists(self.file):
            with open(self.file) as fh:
                for line in fh:
                    try:
                        rec = json.loads(line)
                    except json.JSONDecodeError:
                        continue          # a line cut by a crash: that case runs again
                    self.done[rec.pop("key")] = rec

    def path(self, key):
        return os.path.join(self.directory, "results", f"{key}.pkl") if self.directory \
            else None

    def add(self, key, row):
        if not self.directory:
            return
        rec = {k: v for k, v in row.items() if k not in ("case", "resumed")}
        with open(self.file, "a") as fh:
            fh.write(json.dumps({"key": key, **rec}) + "\n")
            fh.flush()


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
