"""Worker processes for sweeps.

Each worker holds the model (it pickles as its deck text and compiles once per worker) and runs
its cases in the order it gets them, with the next case already queued so that it never waits
for the parent. The case a worker was running when it died, or when it passed the time limit,
is therefore known (the oldest it has not answered): it becomes a row with status ``crashed``
or ``timeout``, the worker is replaced, the cases queued behind it go to the others. Workers
start by ``forkserver`` where the platform has it (never ``fork``: the parent may run
threads), with one BLAS thread each (idle BLAS threads spin and would take the cores the
workers need).
"""
import collections
import multiprocessing as mp
import os
import pathlib
import pickle
import signal
import time
from multiprocessing.connection import wait


def _worker(conn, model):
    from .case import CaseRunner
    runner = CaseRunner(model)
    while True:
        msg = conn.recv()
        if msg is None:
            return
        idx, case, outputs, store = msg
        row, res = runner.run(case, outputs)
        if store and res is not None:
            save_result(res, store)
        conn.send((idx, row))


def save_result(res, path):
    """Write a Result where a sweep keeps it (atomically: a crash leaves no half file)."""
    tmp = f"{path}.{os.getpid()}.tmp"
    with open(tmp, "wb") as fh:
        pickle.dump(res, fh, protocol=pickle.HIGHEST_PROTOCOL)
    os.replace(tmp, path)


_ONE_THREAD = {k: "1" for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
                                 "MKL_NUM_THREADS")}
#: Cases each worker holds: the one it runs and the next.
DEPTH = 2


def _context():
    methods = mp.get_all_start_methods()
    if "forkserver" not in methods:
        return mp.get_context("spawn")
    ctx = mp.get_context("forkserver")
    # workers fork from a server that has imported pysolver once: no import per worker. The
    # server imports with the working folder first on its path: when that folder holds another
    # pysolver (a source checkout beside an installed one) the workers import theirs instead.
    here = pathlib.Path(__file__).resolve().parents[1]
    shadow = pathlib.Path.cwd() / "pysolver"
    if not shadow.exists() or shadow.resolve() == here:
        ctx.set_forkserver_preload(["pysolver", "pysolver.solve.run", "pysolver.batch.case"])
    return ctx


class Pool:
    """`n` workers for `model`; :meth:`run` yields rows as cases finish."""

    def __init__(self, model, n, timeout=None):
        self.model, self.n, self.timeout = model, max(1, int(n)), timeout
        self.ctx = _context()
        self.workers = []

    def _spawn(self):
        parent, child = self.ctx.Pipe()
        saved = {k: os.environ.get(k) for k in _ONE_THREAD}
        os.environ.update(_ONE_THREAD)          # inherited by the process (and forkserver)
        try:
            proc = self.ctx.Process(target=_worker, args=(child, self.model), daemon=True)
            proc.start()
        finally:
            for k, v in saved.items():
                if v is None:
                    os.environ.pop(k, None)
                else:
                    os.environ[k] = v
        child.close()
        return {"proc": proc, "conn": parent, "jobs": collections.deque(), "t0": 0.0}

    def run(self, jobs, outputs):
        """Run jobs (index, case, store path or None); yield (index, row)."""
        pending = collections.deque(jobs)
        self.outputs = outputs
        self.workers = [self._spawn() for _ in range(min(self.n, len(pending)))]
        try:
            while pending or any(w["jobs"] for w in self.workers):
                for w in self.workers:
                    while len(w["jobs"]) < DEPTH and pending:
                        self._give(w, pending.popleft())
                busy = [w for w in self.workers if w["jobs"]]
                limit = None
                if self.timeout is not None:
                    limit = max(0.0, min(w["t0"] for w in busy) + self.timeout
                                - time.perf_counter())
                wait([w["conn"] for w in busy] + [w["proc"].sentinel for w in busy], limit)
                for k in range(len(self.workers)):
                    yield from self._check(k, pending)
        finally:
            self.close()

    def _give(self, w, job):
        if not w["jobs"]:
            w["t0"] = time.perf_counter()       # it starts now
        w["jobs"].append(job)
        idx, case, store = job
        w["conn"].send((idx, case, self.outputs, store))

    def _check(self, k, pending):
        """Rows of worker k's finished cases; its running case's row if it died or ran out of
        time (the cases queued behind go back to the front of `pending`)."""
        w = self.workers[k]
        while w["jobs"] and w["conn"].poll():
            try:
                got = w["conn"].recv()
            except (EOFError, OSError):
                break
            w["jobs"].popleft()
            w["t0"] = time.perf_counter()       # the next one starts
            yield got
        if not w["jobs"]:
            return
        elapsed = time.perf_counter() - w["t0"]
        if not w["proc"].is_alive():
            code = w["proc"].exitcode
            why = (f"killed by signal {signal.Signals(-code).name}" if code and code < 0
                   else f"exit code {code}")
            row = {"status": "crashed", "message": f"the worker process died ({why})",
                   "wall": elapsed, "steps": None}
        elif self.timeout is not None and elapsed > self.timeout:
            w["proc"].kill()
            row = {"status": "timeout", "message": f"stopped after {self.timeout:g} s",
                   "wall": elapsed, "steps": None}
        else:
            return
        w["proc"].join(1.0)
        idx = w["jobs"].popleft()[0]
        pending.extendleft(reversed(w["jobs"]))
        self.workers[k] = self._spawn()
        yield idx, row

    def close(self):
        for w in self.workers:
            try:
                w["conn"].send(None)
            except (OSError, ValueError):
                pass
        deadline = time.perf_counter() + 2.0
        for w in self.workers:
            w["proc"].join(max(0.0, deadline - time.perf_counter()))
            if w["proc"].is_alive():
                w["proc"].kill()
                w["proc"].join(1.0)
        self.workers = []
