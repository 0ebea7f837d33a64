"""Output printing: the actor that acts at print times, the rows it keeps, the progress bar.

The :class:`Printer` writes a row (time, state, its derivative, every request channel) at
each print time of the current Simulate command. Its instants change nothing, so the driver
may hand a whole run of them to the integrator in one call (:meth:`Printer.times_before`,
:meth:`Printer.take`), which the C driver runs without returning to Python.
"""
import copy
import csv
import io
import math
import os
import sys
import time

import numpy as np

from .. import settings
from ..build.bindings import ffi, lib
from ..deck.dimensions import Quantity, header
from ..naming import column_names
from .actors import Actor


def print_times(t0, end, dt):
    """Output times after t0 every dt, ending with end itself (those of :class:`Grid`)."""
    return Grid(t0, end, dt).all()


def command_rows(t0, end, dt):
    """How many output rows printing every dt from t0 to end writes (the end included)."""
    return (end - t0) / dt + 1


def over_budget(rows, ny, nchannels, what):
    """The message when a run would hold `rows` output rows in all, more than the memory budget
    (PYSOLVER_OUTPUT_BUDGET bytes, default 2 GiB) allows, else None. `what` names what asks
    for them ("the Simulate command ending at 3", "Sensor_Event 2's dt = 1e-07 at t = 0.5")."""
    per_row = 8 * (2 * ny + max(nchannels, 1))
    budget = settings.output_budget()
    if rows * per_row <= budget:
        return None
    return (f"{what} would make the run write {rows:.3g} output rows "
            f"({rows * per_row / 2 ** 30:.3g} GiB), more than the output budget of "
            f"{budget / 2 ** 30:.3g} GiB; give a larger print interval or set "
            "PYSOLVER_OUTPUT_BUDGET (bytes)")


class Stream:
    """A CSV file of the run's rows written as they are made (``Model.run(stream=path)``): the
    time and every request channel with an expression or a label, as Result.save writes them
    (names with their units, `units` of deck.dimensions.channel_units).
    Rows from the C driver's batches are written by C as they are made, each handed to the
    operating system at once when the kernel calls user subroutines (a crash of one loses no
    row already made), else at the end of each batch; rows the Python driver makes are
    written, and flushed, once nothing can take them back."""

    def __init__(self, path, kernel, labels, units=None):
        def unit(key):
            return (units or {}).get(key, Quantity(None, None)).unit

        defined = set(kernel.defined_channels.tolist())
        keys, cols = [], []
        for col, (rid, k) in sorted(enumerate(kernel.channels), key=lambda c: tuple(c[1])):
            if rid > 0 and (col in defined or labels.get((rid, k))):    # not joints' (< 0)
                keys.append((rid, k))
                cols.append(col)
        names = [header("time", unit("time"))] + [
            header(name, unit(key)) for key, name in zip(keys, column_names(keys, labels))]
        self.path, self.cols = os.fsencode(path), np.array(cols, dtype=np.int32)
        line = io.StringIO()
        csv.writer(line).writerow(names)
        self.header = line.getvalue().encode()
        self.nout = max(int(kernel.arrays["nout"]), 1)
        err = ffi.new("int *")
        self.st = lib.ps_stream_open(self.path, self.header,
                                     ffi.cast("int *", ffi.from_buffer(self.cols)),
                                     len(self.cols), err)
        if self.st == ffi.NULL:
            raise OSError(err[0], os.strerror(err[0]), os.fsdecode(self.path))

    def rows(self, t, req):
        """Append rows: times (k,) and request rows (k, channels)."""
        t = np.ascontiguousarray(t, dtype=float)
        req = np.ascontiguousarray(np.asarray(req, dtype=float).reshape(len(t), -1))
        if req.shape[1] < self.nout:
            req = np.ascontiguousarray(np.pad(req, ((0, 0), (0, self.nout - req.shape[1]))))
        lib.ps_stream_rows(self.st, ffi.from_buffer("double[]", t),
                           ffi.from_buffer("double[]", req), len(t), self.nout, 1)

    def close(self):
        if self.st is not None:
            lib.ps_stream_close(self.st)
            self.st = None


class Grid:
    """The print times of :func:`print_times`, generated as they are asked for (a long command
    holds no list of its times)."""

    #: Most times one batch call of the integrator gets (it returns to Python after them).
    BATCH = 10000

    def __init__(self, t0=0.0, end=0.0, dt=1.0, empty=False):
        self.t0, self.end, self.dt = t0, end, dt
        n = max(int(math.floor((end - t0) / dt + 1e-9)), 0)
        # grid times within rounding of the end give way to the end itself (a step or two; the
        # bound keeps a grid finer than the times' rounding, refused earlier, from looping)
        for _ in range(4):
            if not (n and t0 + dt * n >= end - 1e-12 * max(1.0, abs(end))):
                break
            n -= 1
        self.n, self.k, self.end_left = n, 1, not empty

    def all(self):
        """Every time of the grid, the end included (an array)."""
        return np.append(self.t0 + self.dt * np.arange(1, self.n + 1, dtype=float), self.end)

    def __bool__(self):
        return self.k <= self.n or self.end_left

    def __len__(self):
        return max(self.n - self.k + 1, 0) + int(self.end_left)

    def __getitem__(self, i):
        if i != 0 or not self:
            raise IndexError(i)
        return self.t0 + self.dt * self.k if self.k <= self.n else self.end

    def popleft(self):
        t = self[0]
        if self.k <= self.n:
            self.k += 1
        else:
            self.end_left = False
        return t

    def upto(self, t_limit):
        """The next times up to t_limit, at most BATCH of them (an array)."""
        last = min(self.n, self.k + self.BATCH - 1)
        out = self.t0 + self.dt * np.arange(self.k, last + 1, dtype=float)
        out = out[:np.searchsorted(out, t_limit, side="right")]
        if len(out) < self.BATCH and last == self.n and len(out) == last - self.k + 1 and \
                self.end_left and self.end <= t_limit:
            out = np.append(out, self.end)
        return out

    def drop(self, count):
        """Drop the next `count` times (those a batch ran through)."""
        grid = min(count, max(self.n - self.k + 1, 0))
        self.k += grid
        if count > grid:
            self.end_left = False


class Rows:
    """Output rows kept as whole (k x n) blocks, as the C driver returns them, plus single rows;
    joined once at the end. Only the last row is addressable. Rows of scalars (times) are
    kept as (k,) blocks."""

    def __init__(self):
        self.parts = []
        self.n = 0

    def append(self, row):
        self.parts.append(np.asarray(row, dtype=float)[None, ...])
        self.n += 1

    def extend(self, block):
        if len(block):
            self.parts.append(np.asarray(block, dtype=float))
            self.n += len(block)

    @property
    def last(self):
        return self.parts[-1][-1]

    def since(self, k0):
        """Rows k0 .. n-1 as one array (the blocks they are in, joined)."""
        parts, n = [], self.n
        for block in reversed(self.parts):
            if n <= k0:
                break
            parts.append(block[max(k0 - (n - len(block)), 0):])
            n -= len(block)
        return np.concatenate(parts[::-1]) if parts else np.zeros((0,))

    def pop(self):
        last = self.parts[-1]
        if len(last) > 1:
            self.parts[-1] = last[:-1]
        else:
            self.parts.pop()
        self.n -= 1
        return last[-1]

    def __len__(self):
        return self.n

    def array(self, width=None):
        """All rows as one (n x width) array, or (n,) for scalar rows (width None). The blocks
        are copied into it one at a time and dropped as they go, so the peak is the rows once
        plus one block, not twice."""
        shape = (self.n,) if width is None else (self.n, width)
        if not self.parts:
            return np.zeros(shape)
        if len(self.parts) > 1:
            out = np.empty(shape)
            i = 0
            self.parts.reverse()
            while self.parts:
                block = self.parts.pop()
                out[i:i + len(block)] = block
                i += len(block)
            self.parts = [out]
        return self.parts[0]


class Progress:
    """A one-line progress bar on standard error, shown only on a terminal for long runs."""

    def __init__(self, t0, t1, enabled):
        self.t0, self.t1 = t0, t1
        self.enabled = sys.stderr.isatty() if enabled is None else enabled
        self.auto = enabled is None
        self.start = time.perf_counter()
        self.last = self.start
        self.shown = False

    def update(self, t, force=False):
        if not self.enabled:
            return
        now = time.perf_counter()
        if not force and (now - self.last < 0.25 or (self.auto and now - self.start < 1.0)):
            return
        self.last = now
        frac = min(max((t - self.t0) / max(self.t1 - self.t0, 1e-300), 0.0), 1.0)
        bar = "#" * int(30 * frac)
        sys.stderr.write(f"\r  [{bar:<30}] {100 * frac:5.1f}%  t = {t:.6g}")
        sys.stderr.flush()
        self.shown = True

    def close(self, t):
        """Show the final state (always when asked for explicitly) and end the line."""
        if self.shown or (self.enabled and not self.auto):
            self.update(t, force=True)
            sys.stderr.write("\n")
            sys.stderr.flush()


class Printer(Actor):
    """Writes output rows at print times; the rows of the whole run end up in the Result."""

    def __init__(self, kernel, bar):
        self.kernel, self.bar = kernel, bar
        self.ts, self.ys, self.yps, self.outs = Rows(), Rows(), Rows(), Rows()
        self.dt = None
        self.end = None
        self.pending = Grid(empty=True)
        self.watchers = []        # actors with on_output, told of every row written
        self.stream = None        # a Stream the rows are written to as they are made
        self.streamed = 0         # rows written to it
        self.c_streams = False    # whether the integrator writes its batches' rows itself

    @property
    def instants(self):
        """None of its own: print times are what the batched path runs through, and every
        row's request channels and reactions are computed in C (with motions and joints each
        row is the end of a step, csrc/ida.c)."""
        return False

    # the schedule --------------------------------------------------------------------
    def begin_command(self, t, end, dt):
        """Print every dt from t to end (a new Simulate command)."""
        self.end, self.dt = end, dt
        self.pending = Grid(t, end, dt)

    def set_interval(self, t, dt):
        """A new print interval from t on (a sensor's dt action). Before the first command
        (a sensor firing at the start) the command's own interval applies, as before."""
        self.dt = dt
        if self.end is not None:
            self.pending = Grid(t, self.end, dt)

    def next_time(self, t):
        return self.pending[0] if self.pending else math.inf

    def times_before(self, t_limit):
        """The pending print times up to t_limit (at most Grid.BATCH), for one batch call of
        the integrator."""
        return self.pending.upto(t_limit)

    def take(self, times, Y, YP, REQ):
        """Keep the rows of a batch the integrator ran through, and drop those times."""
        n = len(times)
        self.pending.drop(n)
        if n:
            self.ts.extend(times)
            self.ys.extend(Y)
            self.yps.extend(YP)
            self.outs.extend(REQ)
            if self.stream is not None:
                if not self.c_streams:
                    self.stream.rows(times, REQ)
                self.streamed = len(self.ts)
            self.bar.update(times[-1])

    # rows ----------------------------------------------------------------------------
    def emit(self, t, y, yp, out=None, exact=True):
        """Write a row at t; a later row at the same time replaces the earlier one. `exact`:
        a dynamic row (its accelerations and reactions made exact: Kernel.outputs), not a
        static one."""
        if self.ts and t < self.ts.last:
            return
        y, yp = np.array(y, dtype=float), np.array(yp, dtype=float)
        # the channels first: a routine that fails at the row ends the run without it
        out = self.kernel.outputs(t, y, yp, exact=exact) if out is None else out
        if self.ts and t == self.ts.last:
            self._drop_last()
        self.ts.append(t)
        self.ys.append(y)
        self.yps.append(yp)
        self.outs.append(out)
        for actor in self.watchers:
            actor.on_output(t, y, yp)
        self.bar.update(t)

    def emit_due(self, step, solver, tstop):
        """Write the rows of every pending print time up to the point a step reached: the
        point itself, or the solver's interpolant within its last step. Returns the Step of an
        interpolation that failed (its row is not written), else None."""
        while self.pending and self.pending[0] <= step.t:
            tp = self.pending.popleft()
            at = step if tp == step.t else solver.interpolate(tp, tstop)
            if not at.success:
                return at
            self.emit(tp, at.y, at.yp)
        return None

    def flush_stream(self, t_safe, inclusive):
        """Write the rows not yet streamed up to t_safe (rows no action can take back)."""
        if self.stream is None or self.streamed >= len(self.ts):
            return
        times = self.ts.since(self.streamed)
        n = int(np.searchsorted(times, t_safe, side="right" if inclusive else "left"))
        if n:
            self.stream.rows(times[:n], self.outs.since(self.streamed)[:n])
            self.streamed += n

    def _drop_last(self):
        self.ts.pop()
        for rows in (self.ys, self.yps, self.outs):
            rows.pop()

    # restore-and-shrink ---------------------------------------------------------------
    def save(self):
        return self.dt, copy.copy(self.pending)

    def restore(self, snapshot, t):
        """Back at time t: rows past t are redone on the schedule of that time (the print
        times after t of the grid then in force, wherever it began)."""
        self.dt, pending = snapshot
        while self.ts and self.ts.last > t:
            self._drop_last()
        self.streamed = min(self.streamed, len(self.ts))
        self.pending = copy.copy(pending)
