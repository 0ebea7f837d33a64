"""Results of a run: time-major arrays, request channels, statistics and writers.

Longer than 420 lines because it is the one object a run is read from: a short, documented
accessor per kind of output (rows, requests, reactions, records, units, files, plots); what
they share lives elsewhere (naming.py: column names and ids; plotting.py, viewer/).
"""
from __future__ import annotations

import csv
import io
import os

import numpy as np

from .deck.dimensions import CONTROLLER, Quantity
from .deck.dimensions import header as _header
from .naming import column_names, element_id

#: The fields of a LoadControl record (pysolver/solve/loadcontrol.py), in order.
_CONTROLLER_FIELDS = tuple(CONTROLLER)


class Result:
    """Outcome of :meth:`Model.run`.

    Attributes
    ----------
    success : bool
        False when the integration failed; ``message`` says why. Output rows up to the failure
        are kept.
    status : int
        0 success, 1 halted by a sensor; negative: an integrator failure code (SUNDIALS
        IDA's), -100 too many steps, -200 sensor events chatter, -300 a static analysis failed,
        -400 a user subroutine failed, -500 the outputs would pass the memory budget, -600
        interrupted (Ctrl-C; the rows up to then are kept), -700 a value became NaN or infinite
        (the message names the element, its expression, the time and the state), -710 the
        answer is past double precision, -720 the initial conditions could not be assembled,
        -730 the constraints were not kept (a joint opened).
    message : str
    t : ndarray, shape (n,)
        Output times (print times of every Simulate command, the initial time first).
    y, yp : ndarray, shape (n, ny)
        States and their time derivatives at the output times; ``state_names`` names columns.
    stats : dict
        ``steps``, ``nres`` (residual evaluations), ``njac`` (Jacobian evaluations),
        ``nfail`` (failed step attempts: error-test and convergence failures together),
        ``ida_nfev``/``ida_njev`` as counted by IDA, ``outputs``; with IDA driven from C also
        ``netf``/``ncfn`` (IDA's error-test and convergence failures) and
        ``growth_limited_at`` (the step at which the automatic step-growth limit for stiff
        penalties came on; None if it did not), None through scikit-sundae.
    timing : dict
        Wall time in seconds: ``setup`` (compile, initial conditions), ``integrate``, ``total``.
    meta : dict
        pysolver version, deck path and SHA-256, integrator options, ``usersubs``: for each
        element defined by a user subroutine, how it runs (traced into the kernel, with the
        expression it became), and ``commands``: each Simulate command's ``analysis`` and
        ``end_time``, in order.
    units, quantities : dict
        Unit and kind of quantity of time and each request channel by its column name, as
        :meth:`columns` names them (properties; docs/usage.md, "Units").
    events : list of pysolver.solve.sensors.Event
        One record per sensor firing: ``time``, ``sensor`` (id), ``label``, ``value`` (the
        sensor's expression then) and ``actions`` taken.
    log : list of str
        The event log: firings, zero-crossing searches, and (verbose sensors) each output row
        while a sensor is active.
    statics : list of pysolver.solve.statics.StaticResult
        One record per static solve (each output of a quasi-static analysis): method,
        iterations, imbalance, error, success, message, compliance.
    """

    _element_labels = {}     # a Result pickled before element labels were kept has none

    def __init__(self, *, t, y, yp, outputs, channels, state_names, success, status, message,
                 stats, timing, meta, column_map, labels=None, events=(), log=(), statics=(),
                 controllers=None, units=None, element_labels=None):
        self.t = np.asarray(t)
        self.y = np.asarray(y)
        self.yp = np.asarray(yp)
        self.success = success
        self.status = status
        self.message = message
        self.stats = stats
        self.timing = timing
        self.meta = meta
        self.state_names = list(state_names)
        self._labels = labels or {}
        self.events = list(events)
        self.log = list(log)
        self.statics = list(statics)
        self._controllers = {lid: {k: np.asarray(v) for k, v in rec.items()}
                             for lid, rec in (controllers or {}).items()}
        # request channels stay one (n, channels) array; request(id) builds its (n, 8) view
        self._outputs = np.asarray(outputs).reshape(len(self.t), len(channels))
        # {(request id, channel): column} and the request ids, sorted (report.column_map)
        self._column, self._request_ids = column_map
        self._requests = {}
        # units by channel (rid, k), "time" and "controller" (deck/dimensions.channel_units)
        self._units = units or {}
        # {"request"/"joint"/"motion"/"controller": {id: label}} (the accessors take labels)
        self._element_labels = element_labels or {}

    @property
    def compliance(self):
        """Compliance matrix (inverse stiffness) at the last static equilibrium, deck length
        per deck force, in the coordinates ``statics[-1].coordinates``; None without statics."""
        return self.statics[-1].compliance if self.statics else None

    @property
    def t_events(self):
        """Times of the sensor firings, shape (k,) (SciPy's name)."""
        return np.array([e.time for e in self.events])

    @property
    def i_events(self):
        """Sensor ids of the firings, shape (k,)."""
        return np.array([e.sensor for e in self.events], dtype=int)

    @property
    def nfev(self):
        """Residual evaluations (SciPy's name for stats["nres"])."""
        return self.stats["nres"]

    @property
    def njev(self):
        """Jacobian evaluations (SciPy's name for stats["njac"])."""
        return self.stats["njac"]

    @property
    def request_ids(self):
        """Ids of the Post_Request elements, sorted."""
        return list(self._request_ids)

    @property
    def joint_ids(self):
        """Ids of the Constraint_Joint elements whose reactions :meth:`joint` gives, sorted."""
        return sorted(-rid for rid, k in self._column if rid < 0 and k == 0)

    def _id(self, kind, key, known):
        """:func:`pysolver.naming.element_id` with this run's labels."""
        return element_id(kind, key, known, self._element_labels.get(kind, {}))

    def request(self, id) -> np.ndarray:
        """Return Post_Request `id` as an (n, 8) array: channels expr1..expr8, NaN for NULL.

        Parameters
        ----------
        id : int, Request or str
            The id, the element (msolve's ``Request``: anything with an integer ``.id``) or
            its label.

        Raises
        ------
        KeyError
            No request has that id or label (the message lists those there are), or the
            label names several.
        TypeError
            `id` is none of these (a float, None, an element of another kind).
        """
        id = self._id("request", id, self._request_ids)
        if id not in self._requests:
            arr = np.full((len(self.t), 8), np.nan)
            for k in range(8):
                if (id, k) in self._column:
                    arr[:, k] = self._outputs[:, self._column[(id, k)]]
            self._requests[id] = arr
        return self._requests[id]

    def _channel(self, rid, k):
        """Channel k of request rid as an (n,) array (NaN when it is NULL)."""
        col = self._column.get((rid, k))
        return self._outputs[:, col] if col is not None else np.full(len(self.t), np.nan)

    @property
    def controller_ids(self):
        """Ids of the LoadControl tasks whose records :meth:`controller` gives."""
        return sorted(self._controllers)

    def controller(self, id) -> dict:
        """Per-update record of LoadControl `id` (id, element or label, as :meth:`request`):
        arrays ``time``, ``target``, ``measured`` and ``filtered`` load, ``displacement``
        (from the start, along the axis), ``A`` (the load/displacement ratio; NaN before any
        load), ``e``, ``Ie``, ``De``, ``velocity`` (for the next interval) and ``clamped``
        (MaxVelocity reached)."""
        return self._controllers[self._id("controller", id, self.controller_ids)]

    @property
    def motion_ids(self):
        """Ids of the motions :meth:`motion` gives, sorted (a LoadControl's is -<its id>)."""
        return sorted(int(n[6:-9]) for n in self.state_names
                      if n.startswith("motion") and n.endswith(".reaction"))

    def motion(self, id) -> np.ndarray:
        """Reaction of Motion_Marker or Motion_Joint `id` at the output times, shape (n,): the
        force (X, Y, Z; a joint's T) or torque (B1, B2, B3; a joint's R) the motion applies to
        I's body along or about its axis of J (B1..B3: the multiplier of the angle's
        equation, a torque about the dual axis of the 1-2-3 sequence, docs/deck-language.md;
        J's body gets the opposite), in model units.
        `id`: the id, the element (``Motion``) or its label, as :meth:`request`."""
        id = self._id("motion", id, self.motion_ids)
        return self.y[:, self.state_names.index(f"motion{id}.reaction")]

    def joint(self, id, jflag: int = 0) -> np.ndarray:
        """Reaction of Constraint_Joint `id` at the output times, shape (n, 8), as
        JOINT(id, jflag, comp, 0) for comp 1..8: |F|, Fx, Fy, Fz, |T|, Tx, Ty, Tz in global
        axes, on I's body at I's origin (jflag 0) or on J's body at J's (jflag 1: the
        opposite force, and the opposite torque less d x F, d = oI - oJ), in model units.
        `id`: the id, the element (``Joint``, ``Jprim``) or its label, as :meth:`request`."""
        id = self._id("joint", id, self.joint_ids)
        cols = [self._outputs[:, self._column[(-id, k)]] for k in range(9)]
        force, torque, d = (np.column_stack(cols[i:i + 3]) for i in (0, 3, 6))
        if jflag:
            torque, force = -torque - np.cross(d, force), -force
        return np.column_stack([np.linalg.norm(force, axis=1), force,
                                np.linalg.norm(torque, axis=1), torque])

    def _quantity(self, key):
        q = self.__dict__.get("_units", {}).get(key)   # a Result pickled before units: none
        return q if q is not None else Quantity(None, None)

    def _named_channels(self):
        """(request id, channel index, bare name, column name) of each channel columns()
        writes (bare: its label or REQ<id>.<k>; column: unique, naming.column_names)."""
        keys = [(rid, k) for rid in self.request_ids for k in range(8)
                if self._labels.get((rid, k)) or not np.all(np.isnan(self._channel(rid, k)))]
        return [(rid, k, self._labels.get((rid, k)) or f"REQ{rid}.{k + 1}", name)
                for (rid, k), name in zip(keys, column_names(keys, self._labels))]

    def columns(self, units: bool = False) -> tuple[list, np.ndarray]:
        """Return (names, 2-D array) of time and every non-NULL request channel.

        Every name is unique (:func:`pysolver.naming.column_names`): a channel's label
        (``z``), else ``REQ<id>.<k>``; a name several channels have gets its request,
        ``z (request 2)``. The CSV header, DataFrame, :attr:`units` use these names.

        Parameters
        ----------
        units : bool, optional
            Names with their unit as the CSV header has them (``"z [mm]"``; a channel with no
            unit keeps its bare name); by default the bare names.
        """
        names = [_header("time", self._quantity("time").unit if units else None)]
        cols = [self.t]
        for rid, k, _, name in self._named_channels():
            names.append(_header(name, self._quantity((rid, k)).unit if units else None))
            cols.append(self._channel(rid, k))
        return names, np.column_stack(cols)

    @property
    def units(self) -> dict:
        """Unit of time and of each request channel by column name (``columns()``'s: ``"z"``,
        ``"z (request 2)"``): a string in the deck's units (``"mm"``, ``"N"``, ``"rad/s"``;
        ``"-"`` dimensionless), None where the channel's expression has no unit (docs/usage.md,
        "Units")."""
        out = {"time": self._quantity("time").unit}
        for rid, k, _, name in self._named_channels():
            out[name] = self._quantity((rid, k)).unit
        return out

    @property
    def quantities(self) -> dict:
        """Kind of quantity of time and each request channel by column name: ``"length"``,
        ``"velocity"``, ``"angle"``, ``"force"``, ``"torque"``, ``"energy"``, ... or None (a
        channel with no unit, or a unit with no common name such as N/mm)."""
        out = {"time": "time"}
        for rid, k, _, name in self._named_channels():
            out[name] = self._quantity((rid, k)).kind
        return out

    def controller_units(self) -> dict:
        """Units of the fields of :meth:`controller` (the same for every task): field name ->
        unit string (None for ``clamped``, a flag)."""
        ctrl = self.__dict__.get("_units", {}).get("controller", {})
        return {k: (ctrl[k].unit if k in ctrl else None) for k in _CONTROLLER_FIELDS}

    def to_dataframe(self):
        """Return a pandas DataFrame indexed by time with one column per request channel.

        Column names are :meth:`columns`' with units, as the CSV header (``"z [mm]"``, the
        index ``"time [s]"``); ``df.attrs["units"]`` is :attr:`units` and
        ``df.attrs["quantities"]`` :attr:`quantities` (names without units).

        Raises
        ------
        ImportError
            pandas is not installed (``pip install pysolver[dataframe]``).
        """
        try:
            import pandas as pd
        except ImportError as err:
            raise ImportError("to_dataframe needs pandas: pip install pandas") from err
        names, data = self.columns(units=True)
        df = pd.DataFrame(data[:, 1:], index=pd.Index(data[:, 0], name=names[0]),
                          columns=names[1:])
        df.attrs["units"] = self.units
        df.attrs["quantities"] = self.quantities
        return df

    def save(self, path: str | os.PathLike) -> str:
        """Write the results: ``.csv`` (time and request channels) or ``.npz`` (everything).
        With LoadControl tasks a ``.csv`` has a sibling ``<stem>_controller<id>.csv`` per task
        (one row per update, the fields of :meth:`controller`); a ``.npz`` holds them as
        ``controller<id>_<field>``, and the CSV's rows and header (``table``,
        ``table_columns``: names with units, ``z [mm]``).

        Returns
        -------
        str
            The path written.
        """
        path = os.fspath(path)
        if path.lower().endswith(".npz"):
            extra = {f"request_{rid}": self.request(rid) for rid in self.request_ids}
            extra.update({f"joint_{jid}": self.joint(jid) for jid in self.joint_ids})
            extra.update({f"controller{lid}_{name}": col
                          for lid, rec in self._controllers.items() for name, col in rec.items()})
            names, table = self.columns(units=True)
            np.savez(path, t=self.t, y=self.y, yp=self.yp, state_names=np.array(self.state_names),
                     success=self.success, message=self.message, t_events=self.t_events,
                     i_events=self.i_events, table=table, table_columns=np.array(names),
                     **extra)
        elif path.lower().endswith(".csv"):
            _write_csv(path, *self.columns(units=True))
            units = self.controller_units()
            for lid, rec in self._controllers.items():
                data = np.column_stack([np.asarray(v, float) for v in rec.values()])
                _write_csv(f"{path[:-4]}_controller{lid}.csv",
                           [_header(k, units.get(k)) for k in rec], data)
        else:
            raise ValueError(f"unknown result format for {path!r}: use .csv or .npz")
        return path

    def plot(self, path: str | os.PathLike | None = None):
        """Plot the run: one panel per kind of quantity with its unit (``length [mm]``) against
        ``time [s]``, sensor events and the ends of Simulate commands marked, LoadControl
        tasks, the path of a point whose x and z (or y) are requested, static equilibria as a
        table with their imbalance; a run with no request channels is a panel that says so
        and names its reactions and states; a failed run's title is ``FAILED: message`` in
        red (docs/usage.md, "Plots").

        Parameters
        ----------
        path : str, optional
            Also write the figure there (PNG, PDF, ... by suffix).

        Returns
        -------
        matplotlib.figure.Figure
            Made without pyplot: Jupyter shows it once, and pyplot holds no open figure.

        Raises
        ------
        ImportError
            matplotlib is not installed (``pip install "pysolver[plot]"``).
        """
        from . import plotting
        return plotting.figure(self) if path is None else plotting.save(self, path)

    def animate(self, model=None, params=None, max_frames: int | None = 4000):
        """The 3-D animation of this run: in Jupyter it shows itself, ``.save(path)`` writes
        it as one HTML file that works offline (docs/animation.md).

        Parameters
        ----------
        model : pysolver.Model, optional
            The model that made this Result; by default the one whose ``run`` did (a Result
            read back from a pickle or a sweep's folder does not keep it).
        params : dict, optional
            The run's numbers, by default those ``model.run(params=...)`` was given.
        max_frames : int or None, optional
            Output rows kept at most (every k-th row and the last beyond; None: all), at
            least 2.

        Returns
        -------
        pysolver.viewer.Animation

        Raises
        ------
        ValueError
            No model is known, the run has no output rows, or `max_frames` is below 2.
        TypeError
            `model` is not a Model (a path: the page is written by ``.save(path)``),
            `params` is not a dict, or `max_frames` is neither an int nor None.
        """
        from .viewer import Animation
        origin = self.__dict__.get("_origin")
        if model is None:
            if origin is None:
                raise ValueError("this Result does not know the model that made it (read "
                                 "back from a file or made outside Model.run): pass it, "
                                 "res.animate(model)")
            model, params = origin[0], params if params is not None else origin[1]
        return Animation(self, model, params=params, max_frames=max_frames)

    def __getstate__(self):
        # the model stays behind: a pickled Result is data (sweep folders, workers)
        return {k: v for k, v in self.__dict__.items() if k != "_origin"}

    def summary(self) -> str:
        """Return the run's outcome and statistics as text."""
        s = self.stats
        lines = [f"success: {self.success} ({self.message})",
                 f"outputs: {len(self.t)} rows" + (f", t = {self.t[0]:g} .. {self.t[-1]:g}"
                                                   if len(self.t) else ""),
                 f"steps: {s['steps']}  residual evals: {s['nres']}  Jacobian evals: "
                 f"{s['njac']}  failed step attempts: {s['nfail']}",
                 f"wall time: setup {self.timing['setup']:.4f} s, integration "
                 f"{self.timing['integrate']:.4f} s"]
        if self.timing.get("compile") or self.timing.get("generate"):
            lines.append(f"kernel: generated C, made in {self.timing['generate']:.3f} s and "
                         f"compiled in {self.timing['compile']:.3f} s (cached for later runs)")
        if s.get("growth_limited_at"):
            lines.insert(3, f"stiff penalty mode: IDA's step growth limited from step "
                            f"{s['growth_limited_at']}")
        if "nevents" in s and (s["nevents"] or s["nroots"]):
            lines.insert(3, f"sensor events: {s['nevents']}  re-armed: {s['nrearms']}  "
                            f"restarts: {s['nrestarts']}  root evaluations: {s['nroots']}")
        # static solves: each one (a few), else a tally (a quasi-static analysis: one per row)
        st = self.statics
        if 0 < len(st) <= 3:
            lines += [f"static at t = {r.time:g}: {r.method}, {r.iterations} iteration"
                      f"{'s' * (r.iterations != 1)}, "
                      f"imbalance {r.imbalance:.3g}, " +
                      ("converged" if r.success else f"failed ({r.message})") for r in st]
        elif st:
            bad = [r for r in st if not r.success]
            methods = ", ".join(f"{m} {sum(r.method == m for r in st)}"
                                for m in dict.fromkeys(r.method for r in st))
            lines.append(f"static solves: {len(st)} ({methods}), " + (
                f"{len(bad)} failed (first at t = {bad[0].time:g}: {bad[0].message})" if bad
                else "all converged") + f", iterations up to {max(r.iterations for r in st)}, "
                f"largest imbalance {max(r.imbalance for r in st):.3g}")
        return "\n".join(lines)

    def __repr__(self):
        return (f"<pysolver.Result success={self.success} n={len(self.t)} "
                f"steps={self.stats.get('steps')} message={self.message!r}>")


def _write_csv(path, names, data):
    """Write a header of `names` and the rows of `data` (numbers as ``repr`` writes them; the
    C writer does ~30 ns a number against ~0.5 us in Python)."""
    from .build.bindings import ffi, lib
    header = io.StringIO()
    csv.writer(header).writerow(names)
    data = np.ascontiguousarray(data, dtype=float).reshape(-1, len(names))
    rc = lib.ps_write_csv(os.fsencode(path), b"w", header.getvalue().encode(),
                          ffi.from_buffer("double[]", data), data.shape[0], data.shape[1])
    if rc:
        raise OSError(rc, os.strerror(rc), path)
