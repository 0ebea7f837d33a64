"""One case of a sweep, run where the model lives (this process, a worker, a Dask worker)."""
import hashlib
import json
import math
import time

import numpy as np

from ..errors import DeckError


def case_key(model, case):
    """A hash of the deck and the case: the name of its result, for resuming a sweep."""
    text = json.dumps({str(k): float(v) if _number(v) else str(v) for k, v in case.items()},
                      sort_keys=True)
    return hashlib.sha256((model.source.sha256 + text).encode()).hexdigest()[:20]


def _number(v):
    try:
        float(v)
        return True
    except (TypeError, ValueError):
        return False


class CaseRunner:
    """Runs cases on one compiled model (compiled once, at the first case)."""

    def __init__(self, model):
        self.model = model
        self._params = None

    def params(self):
        if self._params is None:
            from ..build.params import Parameters
            self._params = Parameters(self.model, self.model._kernel())
        return self._params

    def run(self, case, outputs):
        """Run one case: a row {status, message, wall, steps, outputs...} and the Result (or
        None when the case did not run)."""
        t0 = time.perf_counter()
        try:
            options = self.params().apply(case)
            res = self.model.run(progress=False, **options)
        except DeckError as err:
            return _row("error", str(err), t0), None
        except (ValueError, TypeError) as err:
            return _row("error", f"{type(err).__name__}: {err}", t0), None
        finally:
            if self._params is not None:
                self._params.reset()
        row = _row("ok" if res.success else "failed", res.message, t0)
        row["steps"] = res.stats["steps"]
        for name, spec in (outputs or {}).items():
            row[name] = scalar(res, spec)
        return row, res


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
    """Raise ValueError for an output spec the model cannot answer (before any case runs)."""
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
            if len(parts) != 3 or int(parts[1]) not in model.requests or \
                    not 1 <= int(parts[2]) <= 8:
                raise ValueError(f"output {name!r}: no channel {channel!r}")
        else:
            names = names or model._kernel().layout.names
            if channel not in names:
                raise ValueError(f"output {name!r}: no state {channel!r} (states: "
                                 f"{', '.join(names[:10])}, ...)")
