"""Worker processes for sweeps.

Each worker holds the model (it pickles as its deck text and compiles once per worker) and runs
one case at a time, so the case a worker was running when it died, or when it passed the time
limit, is known: it becomes a row with status ``crashed`` or ``timeout``, the worker is
replaced, and the other cases go on. Workers start by ``forkserver`` where the platform has it
(never ``fork``: the parent may run threads).
"""
import collections
import multiprocessing as mp
import os
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


def _context():
    methods = mp.get_all_start_methods()
    return mp.get_context("forkserver" if "forkserver" in methods else "spawn")


class Pool:
    """`n` workers for `model`; :meth:`run` yields rows as cases finish."""

    def __init__(self, model, n, timeout=None):
        self.model, self.n, self.timeout = model, max(1, int(n)), timeout
        self.ctx = _context()
        self.workers = []

    def _spawn(self):
        parent, child = self.ctx.Pipe()
        proc = self.ctx.Process(target=_worker, args=(child, self.model), daemon=True)
        proc.start()
        child.close()
        return {"proc": proc, "conn": parent, "job": None, "t0": 0.0}

    def run(self, jobs, outputs):
        """Run jobs (index, case, store path or None); yield (index, row)."""
        pending = collections.deque(jobs)
        self.workers = [self._spawn() for _ in range(min(self.n, len(pending)))]
        try:
            while pending or any(w["job"] is not None for w in self.workers):
                for w in self.workers:
                    if w["job"] is None and pending:
                        w["job"] = pending.popleft()
                        w["t0"] = time.perf_counter()
                        idx, case, store = w["job"]
                        w["conn"].send((idx, case, outputs, store))
                busy = [w for w in self.workers if w["job"] is not None]
                limit = None
                if self.timeout is not None:
                    limit = max(0.0, min(w["t0"] for w in busy) + self.timeout
                                - time.perf_counter())
                wait([w["conn"] for w in busy] + [w["proc"].sentinel for w in busy], limit)
                for k, w in enumerate(self.workers):
                    if w["job"] is not None:
                        out = self._check(k, w)
                        if out is not None:
                            yield out
        finally:
            self.close()

    def _check(self, k, w):
        """The row of worker k's case if it finished, died or ran out of time, else None."""
        idx = w["job"][0]
        if w["conn"].poll():
            try:
                got = w["conn"].recv()
            except (EOFError, OSError):
                got = None
            if got is not None:
                w["job"] = None
                return got
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
            return None
        w["proc"].join(1.0)
        self.workers[k] = self._spawn()
        return idx, row

    def close(self):
        for w in self.workers:
            try:
                if w["job"] is None:
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
