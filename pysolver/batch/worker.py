"""A sweep's worker process (started by :class:`pysolver.batch.pool.Worker`).

It is a fresh interpreter (``python -c``) with the parent's ``sys.path``, never a fork or a
``multiprocessing`` child: it never imports the parent's main module, so a sweep needs no
``if __name__ == "__main__":`` guard. It talks to its parent over one socket (pickled
messages):

- ``("model", fingerprint, blob)``: the model and outputs to run (``blob`` a pickle of
  ``(model, outputs)``; the model pickles as its deck text); answered
  ``("ready", fingerprint, error)`` once it is loaded and compiled (error: None or why it
  could not be);
- ``("case", index, case, want_result)``: answered ``(index, row, result)`` with ``result``
  the pickled Result when asked for (the parent writes it: workers write nothing);
- ``None`` or the socket closing: exit.

Ctrl-C is the parent's: the worker ignores SIGINT between runs (it runs in a session of its
own, so a terminal's Ctrl-C does not reach it). A thread watches a pipe whose write end only
the parent holds and ends the process when the parent is gone, even during a long case.
"""
import collections
import os
import pickle
import signal
import sys
import threading
from multiprocessing.connection import Connection

#: Compiled models a worker keeps (by fingerprint), for sweeps that alternate decks.
KEEP = 4


def _watch(fd):
    try:
        while os.read(fd, 64):
            pass
    except OSError:
        pass
    os._exit(0)                           # the parent is gone: nobody wants this case


def main(sock_fd, life_fd):
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_watch, args=(life_fd,), daemon=True).start()
    conn = Connection(sock_fd)
    from ..solve import run as _solvers  # noqa: F401 - imported before "ready", not in a case
    from .case import CaseRunner
    runners = collections.OrderedDict()    # fingerprint -> (CaseRunner or None, outputs/why)
    current = None
    while True:
        try:
            msg = conn.recv()
        except (EOFError, OSError):
            return
        if msg is None:
            return
        if msg[0] == "model":
            _, fp, blob = msg
            if fp not in runners:
                runners[fp] = _load(blob, CaseRunner)
                while len(runners) > KEEP:
                    runners.popitem(last=False)
            runners.move_to_end(fp)
            current = runners[fp]
            conn.send(("ready", fp, None if current[0] is not None else current[1]))
            continue
        _, idx, case, want = msg
        runner, outputs = current
        if runner is None:
            conn.send((idx, {"status": "error", "message": outputs, "wall": 0.0,
                             "steps": None}, None))
            continue
        row, res = runner.run(case, outputs)
        blob = pickle.dumps(res, protocol=pickle.HIGHEST_PROTOCOL) \
            if want and res is not None else None
        conn.send((idx, row, blob))


def _load(blob, CaseRunner):
    """(runner, outputs) of a model message, compiled now (a crash here is the crash of the
    worker's first case); (None, why) when it cannot be loaded."""
    try:
        model, outputs = pickle.loads(blob)
    except Exception as err:  # noqa: BLE001 - reported as every case's error
        return None, f"the worker could not load the model: {type(err).__name__}: {err}"
    runner = CaseRunner(model)
    try:
        runner.params()
    except Exception:  # noqa: BLE001 - kept by the runner: each case's error row
        pass
    return runner, outputs


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]))
