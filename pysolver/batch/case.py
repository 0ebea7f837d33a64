"""One case of a sweep, run where the model lives (a worker process, or this process with
``processes=0``), and the key its row is stored under.

A stored row is reused only while everything its result depends on is the same:
:func:`fingerprint` hashes the deck's text, the Simulate command that replaced its own
(``load(deck, simulate=...)``), what a Python deck built and the user's modules it imports
(:mod:`pysolver.deck.provenance`), the content of every file it names (user subroutine
scripts and C libraries), pysolver's version, the environment settings that change results
(:func:`pysolver.settings.affecting_results`), and the outputs asked for; :func:`case_key`
adds the case.
"""
import hashlib
import json
import math
import numbers
import os
import threading
import time

import numpy as np

from .. import settings
from .._version import __version__
from ..deck.provenance import code_token
from ..errors import DeckError

#: Result.status of a run stopped by Ctrl-C (SIGINT): its case is not a result.
INTERRUPTED = -600


def referenced_files(model):
    """Paths of the files a model's results depend on besides its deck: the scripts and C
    libraries of its user subroutines, sorted."""
    from ..deck.usersubs import elements
    found = set()
    for _, el in elements(model):
        for path in (el.usersub.script, el.usersub.library):
            if path:
                found.add(os.path.abspath(path))
    return sorted(found)


def reusable(model):
    """True when a worker that ran this model may run another deck next: an XML deck without
    user subroutine files (a C library stays loaded, a script's imports stay imported); an
    Adams dataset is data too."""
    return model.source.fmt in ("xml", "adm") and not referenced_files(model)


def fingerprint(model, outputs):
    """A hash of everything a case's result and row depend on besides the case itself."""
    h = hashlib.sha256()

    def put(*parts):
        for p in parts:
            h.update(p if isinstance(p, bytes) else str(p).encode("utf-8", "surrogatepass"))
            h.update(b"\0")

    source = model.source
    put("pysolver", __version__, source.fmt, source.sha256)
    put("simulate", json.dumps(source.simulate, sort_keys=True, default=repr)
        if source.simulate else "")
    put("built", source.built or "")
    for path, digest in source.modules:
        put("module", path, digest)
    for path in referenced_files(model):
        put("file", path, _file_digest(path))
    for name, value in settings.affecting_results():
        put("setting", name, value)
    for name in sorted(outputs or {}, key=str):
        put("output", name, _spec_token(outputs[name]))
    return h.hexdigest()


def _file_digest(path):
    h = hashlib.sha256()
    try:
        with open(path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                h.update(block)
    except OSError as err:
        return f"unreadable: {err.strerror}"
    return h.hexdigest()


def _spec_token(spec):
    """An output spec as text: the spec itself, or a function by its name and code."""
    return code_token(spec) if callable(spec) else "spec:" + str(spec)


def _canonical(v):
    """A case value as JSON that tells a number from a flag or a text (True is not 1)."""
    if type(v) is float and math.isfinite(v):
        return v
    if isinstance(v, (bool, np.bool_)):
        return ["bool", bool(v)]
    if isinstance(v, numbers.Real):
        f = float(v)
        return f if math.isfinite(f) else ["float", repr(f)]
    return [type(v).__name__, str(v)]


def case_key(fp, case):
    """The name of a case's row and Result in a sweep's directory: a hash of the sweep's
    :func:`fingerprint` and the case."""
    text = json.dumps(sorted((str(k), _canonical(v)) for k, v in case.items()))
    return hashlib.sha256((fp + text).encode()).hexdigest()[:24]


class CaseRunner:
    """Runs cases on one compiled model (compiled once, at the first case)."""

    def __init__(self, model):
        self.model = model
        self._params = None
        self._failed = None           # the DeckError compiling the model raised, kept

    def params(self):
        if self._failed is not None:
            raise self._failed
        if self._params is None:
            try:
                self._params = self.model.compile().parameters
            except DeckError as err:
                self._failed = err
                raise
        return self._params

    def run(self, case, outputs):
        """Run one case: a row {status, message, wall, steps, outputs...} and the Result (or
        None when the case did not run). A run stopped by Ctrl-C is status ``interrupted``
        (not a result: the caller stores nothing for it)."""
        t0 = time.perf_counter()
        try:
            options = self.params().apply(case)
            res = self.model.run(progress=False, **options)
        except DeckError as err:
            return _row("error", str(err), t0), None
        except Exception as err:  # noqa: BLE001 - any exception is this case's error row
            return _row("error", f"{type(err).__name__}: {err}", t0), None
        finally:
            if self._params is not None:
                self._params.reset()
        if _interrupted(res):
            return _row("interrupted", res.message, t0), None
        row = _row("ok" if res.success else "failed", res.message, t0)
        row["steps"] = res.stats["steps"]
        for name, spec in (outputs or {}).items():
            try:
                row[name] = scalar(res, spec)
            except Exception as err:  # noqa: BLE001 - a user's output function
                return _row("error", f"output {name!r}: {type(err).__name__}: {err}", t0), None
        return row, res


def _interrupted(res):
    """The run was stopped by Ctrl-C: its status says so, or (a Ctrl-C while the initial
    conditions are computed is reported as a failed user subroutine) the kernel's flag, which
    a run arms in the main thread only."""
    if res.status == INTERRUPTED:
        return True
    if threading.current_thread() is threading.main_thread():
        global _lib
        if _lib is None:
            from ..build.bindings import lib as _lib
        return bool(_lib.ps_interrupted())
    return False


_lib = None


def _row(status, message, t0):
    return {"status": status, "message": message, "wall": time.perf_counter() - t0,
            "steps": None}


def scalar(res, spec):
    """One number of a Result: a callable of it, or ``"FUNC:CHANNEL"`` with FUNC one of final,
    max, min, mean and CHANNEL ``request/ID/K`` (channel K = 1..8 of Post_Request ID) or a
    state name (``body2.x``, ``motion1.reaction``); or ``"first_event"`` (time of the first
    sensor firing, NaN if none) or ``"steps"``."""
    if callable(spec):
        return float(spec(res))
    if spec == "first_event":
        return float(res.events[0].time) if res.events else math.nan
    if spec == "steps":
        return float(res.stats["steps"])
    func, _, channel = str(spec).partition(":")
    if channel.startswith("request/"):
        _, rid, k = channel.split("/")
        data = res.request(int(rid))[:, int(k) - 1]
    else:
        data = res.y[:, res.state_names.index(channel)]
    if len(data) == 0:
        return math.nan
    return float({"final": lambda a: a[-1], "max": np.nanmax, "min": np.nanmin,
                  "mean": np.nanmean}[func](data))


def check_outputs(model, outputs):
    """Raise ValueError for an output spec the model cannot answer (before any case runs).
    State names come from the state layout, without compiling the model: nothing here runs
    a user subroutine."""
    names = None
    for name, spec in (outputs or {}).items():
        if callable(spec) or spec in ("first_event", "steps"):
            continue
        func, _, channel = str(spec).partition(":")
        if func not in ("final", "max", "min", "mean"):
            raise ValueError(f"output {name!r}: {spec!r} must be FUNC:CHANNEL with FUNC one of "
                             "final, max, min, mean")
        if channel.startswith("request/"):
            parts = channel.split("/")
            if len(parts) != 3 or not all(p.isdigit() for p in parts[1:]) or \
                    int(parts[1]) not in model.requests or not 1 <= int(parts[2]) <= 8:
                raise ValueError(f"output {name!r}: no channel {channel!r}")
        else:
            if names is None:
                from ..build.compiler import Layout
                names = Layout(model).names
            if channel not in names:
                raise ValueError(f"output {name!r}: no state {channel!r} (states: "
                                 f"{', '.join(names[:10])}, ...)")
