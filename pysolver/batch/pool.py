"""Worker processes for sweeps.

Each worker is a fresh interpreter running :mod:`pysolver.batch.worker` (never a fork of this
process and never a ``multiprocessing`` child: it does not import the main module, so a plain
script needs no ``if __name__ == "__main__":``, and it can be started from a daemonic process
such as a Dask worker's). It loads the model from its deck text and compiles it once, then
runs its cases in the order it gets them, with the next case already queued so that it never
waits for the parent. The case a worker was running when it died, or when it passed the time
limit, is therefore known (the oldest it has not answered): it becomes a row with status
``crashed`` or ``timeout``, the worker is replaced, the cases queued behind it go to the
others. Workers run with one BLAS thread each (idle BLAS threads spin and would take the cores
the workers need) and in a session of their own (Ctrl-C is the parent's to handle).

Idle workers are kept for the next sweep of this process (starting one costs an interpreter
and pysolver's imports, about a second): one that ran a deck with user subroutine files or a
Python deck is given again only to a sweep of the same fingerprint (a C library stays loaded,
a script's imports stay imported); the others to any sweep. A worker started in another
environment (the settings that change results, :func:`pysolver.settings.affecting_results`)
is not reused, nor one still loading its model.
"""
import atexit
import collections
import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from multiprocessing.connection import Connection, wait

from .. import settings

_ONE_THREAD = {k: "1" for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
                                 "MKL_NUM_THREADS")}
#: Cases each worker holds: the one it runs and the next.
DEPTH = 2
#: Seconds a worker may take to start, load and compile its model before the case it holds is
#: stopped as ``timeout``, when the sweep has a time limit and no ``startup_timeout`` of its
#: own (at least that limit: generating and compiling a large deck's C takes a while).
STARTUP = 300.0
#: Workers in a row that die while loading the model before the cases not yet given to one
#: are rows ``crashed`` without running.
LOAD_DEATHS = 3
#: Workers in a row that run out of time while loading the model before the cases not yet
#: given to one are rows ``timeout`` without running (each one waited its startup allowance).
LOAD_HANGS = 2
#: Idle workers kept for later sweeps of this process.
KEEP_IDLE = max(2, os.cpu_count() or 1)

_BOOT = ("import json, sys; sys.path[:] = json.loads(sys.argv[1]); "
         "from pysolver.batch.worker import main; main(int(sys.argv[2]), int(sys.argv[3]))")


class Worker:
    """One worker process and the cases it holds."""

    def __init__(self):
        ours, theirs = socket.socketpair()
        life_r, life_w = os.pipe()
        try:
            self.proc = subprocess.Popen(
                [sys.executable, "-c", _BOOT, json.dumps(sys.path), str(theirs.fileno()),
                 str(life_r)],
                pass_fds=(theirs.fileno(), life_r), env=dict(os.environ, **_ONE_THREAD),
                stdin=subprocess.DEVNULL, start_new_session=True)
        except BaseException:
            ours.close()
            os.close(life_w)
            raise
        finally:
            theirs.close()
            os.close(life_r)
        self.conn = Connection(ours.detach())
        self.life = life_w
        self.settings = settings.affecting_results()     # its environment's, for reuse
        self.fp, self.ready, self.pure = None, False, True
        self.jobs = collections.deque()
        self.t0 = time.perf_counter()

    def load(self, fp, blob, pure):
        """Give the worker a model (nothing to send when it has this one)."""
        self.pure = self.pure and pure
        if self.fp == fp:
            return
        self.fp, self.ready, self.t0 = fp, False, time.perf_counter()
        self.send(("model", fp, blob))

    def send(self, msg):
        try:
            self.conn.send(msg)
        except OSError:
            pass                      # it died: the next check finds it and says how

    def alive(self):
        return self.proc.poll() is None

    def stop(self, kill=False):
        if kill:
            self.proc.kill()
        else:
            self.send(None)
        self.conn.close()
        if self.life is not None:
            os.close(self.life)
            self.life = None
        try:
            self.proc.wait(0.5 if kill else 2.0)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()

    def death(self):
        """Why the process ended."""
        try:
            code = self.proc.wait(5.0)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            code = self.proc.wait()
        if code < 0:
            try:
                return f"killed by signal {signal.Signals(-code).name}"
            except ValueError:
                return f"killed by signal {-code}"
        return f"exit code {code}"


_IDLE = []
_LOCK = threading.Lock()


def _take(fp, pure, n):
    """Up to n idle workers that may run the model `fp`: its own first."""
    got = []
    now = settings.affecting_results()
    with _LOCK:
        for w in list(_IDLE):
            if not w.alive() or w.settings != now:   # dead, or started in another environment
                _IDLE.remove(w)
                w.stop(kill=True)
        for match in (lambda w: w.fp == fp, lambda w: pure and w.pure):
            for w in list(_IDLE):
                if len(got) < n and match(w):
                    _IDLE.remove(w)
                    got.append(w)
    return got


def _give_back(w):
    with _LOCK:
        _IDLE.append(w)
        extra = _IDLE[:-KEEP_IDLE] if len(_IDLE) > KEEP_IDLE else []
        del _IDLE[:len(extra)]
    for old in extra:
        old.stop()


def _forget_in_child():
    """A fork of this process: the idle workers are the parent's (not to use, not to stop)."""
    global _LOCK
    _LOCK = threading.Lock()
    _IDLE.clear()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_in_child)


@atexit.register
def shutdown():
    """Stop the idle workers (they also end by themselves when this process ends)."""
    with _LOCK:
        idle = list(_IDLE)
        _IDLE.clear()
    for w in idle:
        w.stop()


class Pool:
    """`n` workers for one model; :meth:`run` yields rows as cases finish.

    Parameters
    ----------
    payload : tuple
        (fingerprint, blob, pure): the model's :func:`~pysolver.batch.case.fingerprint`, the
        pickle of (model, outputs) a worker loads, and whether a worker that ran it may run
        other decks later (:func:`~pysolver.batch.case.reusable`).
    n : int
    timeout : float, optional
        Seconds a case may run before its worker is killed.
    startup : float, optional
        Seconds a worker may take to load and compile the model (default: with a `timeout`,
        the larger of it and :data:`STARTUP`; without one, no limit).
    """

    def __init__(self, payload, n, timeout=None, startup=None):
        self.fp, self.blob, self.pure = payload
        self.n, self.timeout = max(1, int(n)), timeout
        self.startup = startup if startup is not None else \
            None if timeout is None else max(timeout, STARTUP)
        self.workers = []
        self.load_deaths = 0              # workers in a row that died before they were ready
        self.load_hangs = 0               # workers in a row out of time before they were ready

    def _new(self):
        w = Worker()
        w.load(self.fp, self.blob, self.pure)
        return w

    def run(self, jobs, want=False):
        """Run jobs (index, case); yield (index, row, pickled Result or None). With `want`
        the Result of each case that ran comes back too. A case stopped by Ctrl-C in its
        worker raises KeyboardInterrupt here (and is not yielded)."""
        pending = collections.deque(jobs)
        self.want = want
        count = min(self.n, len(pending))
        self.workers = _take(self.fp, self.pure, count)
        for w in self.workers:
            w.load(self.fp, self.blob, self.pure)
        while len(self.workers) < count:
            self.workers.append(self._new())
        finished = False
        try:
            while pending or any(w.jobs for w in self.workers if w is not None):
                for k, w in enumerate(self.workers):
                    if w is None:                        # the model never loads: none
                        continue
                    if pending and w.conn.closed:        # it died idle: a new one
                        w = self.workers[k] = self._new()
                    while len(w.jobs) < DEPTH and pending:
                        self._give(w, pending.popleft())
                busy = [w for w in self.workers if w is not None and w.jobs]
                limits = [self._limit(w) for w in busy]
                limits = [x for x in limits if x is not None]
                wait([w.conn for w in busy],
                     max(0.0, min(limits) - time.perf_counter()) if limits else None)
                for k in range(len(self.workers)):
                    yield from self._check(k, pending)
            finished = True
        finally:
            self.close(finished)

    def _limit(self, w):
        """When the case worker w runs must end (perf_counter time), or None."""
        limit = self.timeout if w.ready else self.startup
        return None if limit is None else w.t0 + limit

    def _give(self, w, job):
        if not w.jobs and w.ready:
            w.t0 = time.perf_counter()       # it starts now
        w.jobs.append(job)
        idx, case = job
        w.send(("case", idx, case, self.want))

    def _check(self, k, pending):
        """Rows of worker k's finished cases; its running case's row if it died or ran out of
        time (the cases queued behind go back to the front of `pending`)."""
        w = self.workers[k]
        if w is None:
            return
        dead = False
        while w.jobs:
            try:
                if not w.conn.poll():
                    break
                got = w.conn.recv()
            except (EOFError, OSError):
                dead = True
                break
            if got[0] == "ready":
                if got[1] == w.fp:
                    w.ready, w.t0 = True, time.perf_counter()
                continue
            w.jobs.popleft()
            w.t0 = time.perf_counter()       # the next one starts
            self.load_deaths = self.load_hangs = 0
            idx, row, blob = got
            if row["status"] == "interrupted":
                raise KeyboardInterrupt(f"case {idx}: {row['message']}")
            yield idx, row, blob
        if not w.jobs:
            if dead or not w.alive():
                w.stop(kill=True)             # replaced when it is given a case
            return
        now = time.perf_counter()
        limit = self._limit(w)
        why = None
        if dead or not w.alive():
            why = w.death()
            row = {"status": "crashed", "message": f"the worker process died ({why})",
                   "wall": now - w.t0, "steps": None}
            self.load_deaths = 0 if w.ready else self.load_deaths + 1
        elif limit is not None and now > limit:
            w.proc.kill()
            msg = f"stopped after {self.timeout:g} s" if w.ready else \
                f"stopped: the worker did not load and compile the model within " \
                f"{self.startup:g} s"
            row = {"status": "timeout", "message": msg, "wall": now - w.t0, "steps": None}
            self.load_hangs = 0 if w.ready else self.load_hangs + 1
        else:
            return
        w.stop(kill=True)
        idx = w.jobs.popleft()[0]
        pending.extendleft(reversed(w.jobs))
        w.jobs.clear()
        yield idx, row, None
        # the model kills (or never finishes loading in) every worker that loads it: the
        # other cases would do the same, so they are rows now, without a worker
        if why is not None and self.load_deaths >= LOAD_DEATHS:
            msg = (f"not run: the worker process died while loading and compiling the model, "
                   f"{self.load_deaths} times in a row (the last: {why})")
            status = "crashed"
        elif why is None and self.load_hangs >= LOAD_HANGS:
            msg = (f"not run: the model did not finish loading and compiling in a worker "
                   f"within {self.startup:g} s, {self.load_hangs} times in a row (a deck, user "
                   "subroutine or compiler that hangs; startup_timeout=, --startup-timeout, "
                   "sets the allowance)")
            status = "timeout"
        else:
            self.workers[k] = self._new()
            return
        self.workers[k] = None
        while pending:
            yield pending.popleft()[0], {"status": status, "message": msg, "wall": 0.0,
                                         "steps": None}, None

    def close(self, finished=True):
        """Keep healthy idle workers for later sweeps; stop the others (at once when the
        sweep did not finish: their cases are not wanted)."""
        for w in self.workers:
            if w is None:
                continue
            if finished and not w.jobs and w.ready and w.alive():
                _give_back(w)
            else:
                w.stop(kill=True)             # not wanted, or still loading the model
        self.workers = []


def run_chunk(payload, chunk, timeout, want, startup=None):
    """Cases on one worker of this process (a Dask task): a list of (index, row, Result
    pickle or None)."""
    return list(Pool(payload, 1, timeout, startup).run(chunk, want))
