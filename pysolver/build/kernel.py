"""A compiled scene bound to the C kernel: psModel + psData and fast call wrappers."""
import functools
import re

import numpy as np

from ..deck import usersubs
from ..options import SPARSE_THRESHOLD
from . import compliance, usercalls
from .bindings import ffi, lib
from .compiler import Compiler
from .consistent import consistent, start

ROUNDING = 1e-10     # trial times this close (times |t|) to a non-finite residual: rounding


class UserFailure(Exception):
    """A kernel call failed for good on the scikit-sundae path: a user subroutine's error,
    or a non-finite value IDA's trial steps cannot step around."""


class Kernel:
    """Owns the arrays of one compiled scene and its workspace.

    Parameters
    ----------
    model : Model
        A validated model.
    conservative : bool, optional
        Compile without velocity-dependent terms (penalty1 and velocity measures read as 0),
        for MKEAM's undamped motion.
    kind : {"auto", "generated", "tapes"}, optional
        "generated" or "auto": generate the scene's C, compile it (cached on disk, see
        :mod:`pysolver.build.codegen`) and call it; the tape interpreter runs when that is not
        possible ("auto" says why in :attr:`codegen`; "generated" too, it never fails a run).
        "tapes": interpret the tapes.
    removed : set of (int, int), optional
        Redundant joint equations left out: (joint id, equation index).

    Attributes
    ----------
    ny : int
        Number of states.
    layout : compiler.Layout
        Where each body's coordinates are in the state.
    channels : list of (request id, channel index)
        Meaning of each entry of :meth:`outputs`.
    codegen : dict
        Which kernel runs: ``{"kernel": "generated", "generate": s, "compile": s, "cached": bool,
        "path": ...}`` or ``{"kernel": "tapes", "why": ...}``.
    """

    def __init__(self, model, conservative=False, kind="auto", removed=()):
        usersubs.resolve(model)         # Python user subroutines traced into expressions
        usercalls.bind(model)           # the others called from the kernel
        comp = Compiler(model, conservative, removed)
        arrays = comp.compile()
        self.layout = comp.layout
        self.channels = comp.channels
        self.sensor_ids = sorted(model.sensors)
        self.motion_tags = self.layout.motion_tags         # id -> Motion_Marker / Motion_Joint
        self.evaluate_ids = sorted(model.evaluates)
        self.evaluate_tapes = comp.evaluate
        self.control_tapes = comp.ctrl
        self.params = comp.params               # sweep parameters: path -> slot in consts
        self.marker_index = dict(comp.midx)     # marker id -> its row in the marker arrays
        self.forces_use_senval = comp.forces_use_senval
        self.model_calls_routines = bool(model.user_routines)   # C or untraced Python
        self.elements = comp.elements      # the element table: (kind, id, tape, ints)
        self.motion_slots = comp.motion_slots   # motion id -> (tape, slot) of its measure
        self.joint_ic = comp.joint_ic           # the joints' initial conditions (icjoint)
        self.nsensor = arrays["nsensor"]
        self.ny = arrays["ny"]
        self.ntape = arrays["ntape"]
        self._keep = []
        m = ffi.new("psModel *")
        # each compiled array or number into its psModel field of the same name (a new
        # element's sizes need no list here: a whole number is an int field)
        for key, val in arrays.items():
            if isinstance(val, (int, np.integer)) and not isinstance(val, bool):
                setattr(m, key, int(val))
            elif isinstance(val, float) or key == "gravity":
                setattr(m, key, list(val) if key == "gravity" else float(val))
            elif key in ("user_fn", "user_name"):     # the routines, their names
                items = val if key == "user_fn" else [ffi.new("char[]", s.encode()) for s in val]
                table = ffi.new("void *[]" if key == "user_fn" else "char *[]", items or [ffi.NULL])
                self._keep += [items, table]
                setattr(m, key, table)
            else:
                ctype = "int *" if val.dtype == np.int32 else "double *"
                if val.size == 0:
                    val = np.zeros(1, dtype=val.dtype)
                self._keep.append(val)
                setattr(m, key, ffi.cast(ctype, ffi.from_buffer(val)))
        self.arrays = arrays
        self.m = m
        stride = arrays["hd_stride"]
        self._work = {
            "slots": np.zeros(arrays["max_slots"] * stride),
            "bcache": np.zeros(arrays["max_bslots"] * 32 * stride),
            "tmp": np.zeros(lib.PS_TMP_TOTAL * stride),
            "res": np.zeros(max(2 * self.ny, 1)),
            "trip": np.zeros(1),
            # stored Sensor_Evaluate values, then each LoadControl's velocity
            "senval": np.zeros(max(len(model.evaluates) + len(model.controls), 1)),
            "sensor_f": np.zeros(max(self.nsensor, 1)),
            "sensor_side": np.ones(max(self.nsensor, 1)),
            "user_cache": np.zeros(max(arrays["nusercache"], 1) * lib.PS_USER_CACHE),
            "bad_y": np.zeros(self.ny),      # the state of the last non-finite value
            "trig": np.full(3 * max(self.ny, 1), np.nan),   # generated C's psg_trig
        }
        self.armed = np.ones(max(self.nsensor, 1), dtype=np.int32)
        self._flags = tuple(np.zeros(max(self.nsensor, 1), dtype=np.int32) for _ in range(2))
        self.d = ffi.new("psData *")
        self._set_work()
        self._out = np.zeros(max(arrays["nout"], 1))
        self._sparse = None
        self._cyp = None                 # consistent_yp's work arrays, made on first use
        self.codegen = {"kernel": "tapes", "why": "kernel='tapes' asked for"}
        if kind != "tapes":
            self._generate()
        self._bind()
        if len(self.layout.lam):
            compliance.init_compliance(self, (UserFailure,))

    def _generate(self):
        """Attach the generated C of this scene (pysolver.build.codegen), if it can be made."""
        from . import codegen
        info = codegen.attach(self, lib, ffi)
        gen = info.pop("gen", None)
        if gen is not None:
            self.m.gen = gen
            self._work["trip"] = np.zeros(max(gen.ntrip, 1))
            self._set_work()
        if info["kernel"] == "generated":    # reported in the timing of the first run
            info["generate_unreported"], info["compile_unreported"] = info["generate"], \
                info["compile"]
        self.codegen = info

    def _set_work(self):
        for key, val in self._work.items():
            setattr(self.d, key, ffi.cast("double *", ffi.from_buffer(val)))
        self.d.sensor_armed = ffi.cast("int *", ffi.from_buffer(self.armed))

    @functools.cached_property
    def defined_channels(self):
        """Columns of the request channels that have an expression (not NULL)."""
        return np.flatnonzero(self.arrays["out_tape"][:len(self.channels)] >= 0)

    @property
    def bad_state(self):
        """The state (t, y) at which the kernel last found a non-finite value (see ps_residual);
        meaningful while ``d.bad_kind`` is set."""
        return self.d.bad_t, self._work["bad_y"].copy()

    @property
    def senval(self):
        """Stored Sensor_Evaluate values, in evaluate-id order (a view the kernel reads)."""
        return self._work["senval"]

    @property
    def sensor_side(self):
        """Side (+1 above, -1 below the value) from which each armed EQ sensor approaches."""
        return self._work["sensor_side"]

    @property
    def sensor_f(self):
        """Sensor expressions at the last root evaluation, in sensor-id order."""
        return self._work["sensor_f"]

    def roots(self, t, y, yp, g):
        """Fill g with every sensor's root function (see ps_roots)."""
        fb = ffi.from_buffer
        return lib.ps_roots(self.m, self.d, t, fb("double[]", y), fb("double[]", yp),
                            fb("double[]", g))

    def sensor_status(self, t, y, yp):
        """Every sensor at (t, y, yp) by the kernel's rules (ps_sensor_status): its expression,
        whether its condition holds, whether a fired sensor may re-arm (copies)."""
        fb = ffi.from_buffer
        holds, rearms = self._flags
        lib.ps_sensor_status(self.m, self.d, t, fb("double[]", np.ascontiguousarray(y, float)),
                             fb("double[]", np.ascontiguousarray(yp, float)),
                             ffi.cast("int *", fb(holds)), ffi.cast("int *", fb(rearms)))
        n = self.nsensor
        return self.sensor_f[:n].copy(), holds[:n].astype(bool), rearms[:n].astype(bool)

    def eval_tape(self, which, t, y, yp):
        """Evaluate one expression tape at (t, y, yp) (order 0): ``which`` is
        ``self.evaluate_tapes[k]`` (Sensor_Evaluate k in id order) or ``self.control_tapes[k]``
        (LoadControl k's target load)."""
        tape, slot = which
        return lib.ps_eval_tape(self.m, self.d, tape, slot, t,
                                ffi.from_buffer("double[]", np.ascontiguousarray(y, float)),
                                ffi.from_buffer("double[]", np.ascontiguousarray(yp, float)))

    def penalty_loads(self, t, y, yp):
        """Generalized forces of all penalties at (t, y, yp) on the velocity rows, model force
        units (a new array)."""
        q = np.zeros(self.ny)
        fb = ffi.from_buffer
        lib.ps_penalty_loads(self.m, self.d, t, fb("double[]", np.ascontiguousarray(y, float)),
                             fb("double[]", np.ascontiguousarray(yp, float)),
                             fb("double[]", q))
        return q

    def sparsity(self):
        """Return the iteration matrix's structure as a scipy CSC matrix (built once).

        Each structural nonzero is the kernel writing a derivative there for some state; the
        kernel's triplets are mapped onto this matrix's data array in ``jacobian_csc``.
        """
        if self._sparse is None:
            import scipy.sparse as sp
            n = lib.ps_jacobian_pattern(self.m, self.d, ffi.NULL, ffi.NULL)
            rows = np.zeros(max(n, 1), dtype=np.int32)
            cols = np.zeros(max(n, 1), dtype=np.int32)
            lib.ps_jacobian_pattern(self.m, self.d, ffi.cast("int *", ffi.from_buffer(rows)),
                                    ffi.cast("int *", ffi.from_buffer(cols)))
            rows, cols = rows[:n], cols[:n]
            self._triplets = (rows, cols)
            pattern = sp.csc_matrix((np.ones(n), (rows, cols)), shape=(self.ny, self.ny))
            pattern.sum_duplicates()
            pattern.sort_indices()
            # data index of each (row, col): position of row within its column's slice
            lookup = {(int(r), int(c)): k for c in range(self.ny)
                      for k, r in zip(range(pattern.indptr[c], pattern.indptr[c + 1]),
                                      pattern.indices[pattern.indptr[c]:pattern.indptr[c + 1]])}
            tmap = np.array([lookup[(int(r), int(c))] for r, c in zip(rows, cols)],
                            dtype=np.int32)
            self._work["trip"] = np.zeros(max(n, 1))
            self._set_work()
            self._sparse = (pattern, tmap, n)
        return self._sparse[0]

    def _bind(self):
        m, d, fb = self.m, self.d, ffi.from_buffer
        res_c, jac_c = lib.ps_residual, lib.ps_jacobian

        bad_t = [None]

        def residual(t, y, yp, res):
            rc = res_c(m, d, t, fb("double[]", y), fb("double[]", yp), fb("double[]", res))
            if rc:
                # a non-finite residual is recoverable for IDA, unless trial times have closed
                # in on it to rounding level (the solution runs into it); a user subroutine's
                # error is not (scikit-sundae retries on any return code, so it is raised)
                if d.user_error:
                    raise UserFailure(self.message)
                if bad_t[0] is not None and 0 < abs(t - bad_t[0]) <= ROUNDING * abs(t):
                    raise UserFailure(self.message)
                bad_t[0] = t
            return rc

        def jacobian(t, y, yp, cj, jac):
            return jac_c(m, d, t, fb("double[]", y), fb("double[]", yp), cj, fb("double[]", jac))

        def jacobian_ida(t, y, yp, res, cj, jac):
            rc = jac_c(m, d, t, fb("double[]", y), fb("double[]", yp), cj, fb("double[]", jac))
            if rc and d.user_error:
                raise UserFailure(self.message)
            return rc

        self.residual = residual
        self.jacobian = jacobian
        self.jacobian_ida = jacobian_ida      # scikit-sundae's jacfn signature, no extra frame

    def bandwidths(self):
        """(mu, ml): upper and lower bandwidths of the iteration matrix's structure."""
        self.sparsity()
        rows, cols = self._triplets
        if len(rows) == 0:
            return 0, 0
        return int(max(0, (cols - rows).max())), int(max(0, (rows - cols).max()))

    def band_map(self, mu, ml):
        """Index in SUNDIALS band storage (column-major, leading dimension smu + ml + 1 with
        smu = mu + ml stored upper diagonals, also where mu + ml passes n - 1: the layout
        SUNBandMatrix makes, which ps_ida_init checks) of each Jacobian triplet."""
        self.sparsity()
        rows, cols = self._triplets
        smu = mu + ml
        ldim = smu + ml + 1
        return np.ascontiguousarray(cols * ldim + (rows - cols + smu), dtype=np.int32)

    def csc_map(self):
        """Index into the CSC data array of :meth:`sparsity` of each kernel triplet (int32)."""
        self.sparsity()
        return self._sparse[1]

    def jacobian_csc_fn(self):
        """Return a scikit-sundae ``jacfn`` filling the CSC data array of :meth:`sparsity`."""
        self.sparsity()
        pattern, tmap, ntrip = self._sparse
        m, d, fb = self.m, self.d, ffi.from_buffer
        cmap = ffi.cast("int *", fb(tmap))
        nnz = pattern.nnz
        csc_c = lib.ps_jacobian_csc

        def jacobian(t, y, yp, res, cj, data):
            rc = csc_c(m, d, t, fb("double[]", y), fb("double[]", yp), cj, cmap, ntrip,
                       fb("double[]", data), nnz)
            if rc and d.user_error:
                raise UserFailure(self.message)
            return rc

        jacobian.keep_alive = tmap   # cmap points into it
        return jacobian

    @property
    def counters(self):
        """Kernel call counters: residual and Jacobian evaluations."""
        d = self.d
        return {"nres": d.nres, "njac": d.njac, "attempts": d.ntimes, "nfail": d.nfail,
                "nroots": d.nroots}

    def reset_counters(self):
        """Zero the call and step-attempt counters."""
        d = self.d
        d.nres = d.njac = d.ntimes = d.nfail = d.nroots = 0
        d.user_error = d.step_limit = d.steps_exceeded = d.out_nonfinite = 0
        self._work["user_cache"][:] = 0.0     # user subroutines are evaluated afresh

    @property
    def message(self):
        """Message of the last kernel error (a held state named, csrc/ida.c)."""
        msg = ffi.string(self.d.msg).decode(errors="replace")
        held = re.match(r"state (\d+) was held", msg)
        return msg if held is None else self.layout.names[int(held[1])] + msg[held.end(1):]

    def outputs(self, t, y, yp, out=None, exact=True):
        """Request channels at (t, y, yp) (NaN if NULL), a copy or into `out`; `exact`: a dynamic
        row's accelerations and reactions made exact first. UserFailure (.t) if a routine fails."""
        fb, m, d, row = ffi.from_buffer, self.m, self.d, self._out if out is None else out
        y, yp, before = fb("double[]", y), fb("double[]", yp), d.user_error
        if exact and d.rows != ffi.NULL:
            lib.ps_row_exact(m, d, d.rows, t, y, yp)
        lib.ps_outputs(m, d, t, y, yp, fb("double[]", row))
        if d.user_error and not before:     # the run ends at the row, without it
            err = UserFailure(self.message)
            err.t = t
            raise err
        return self._out[:len(self.channels)].copy() if out is None else None

    def power(self, y, yp):
        """Rate of change of the kinetic energy (model units)."""
        fb = ffi.from_buffer
        return lib.ps_power(self.m, fb("double[]", y), fb("double[]", yp))

    def residual_array(self, t, y, yp):
        """Return F(t, y, yp) as a new array (convenience for tests and tools)."""
        res = np.zeros(self.ny)
        self.residual(t, np.ascontiguousarray(y, float), np.ascontiguousarray(yp, float), res)
        return res

    def jacobian_csc_array(self, t, y, yp, cj):
        """Return the iteration matrix through the sparse path, as a scipy CSC matrix."""
        pattern = self.sparsity().copy()
        fn = self.jacobian_csc_fn()
        data = np.zeros(pattern.nnz)
        fn(t, np.ascontiguousarray(y, float), np.ascontiguousarray(yp, float), None, cj, data)
        pattern.data[:] = data
        return pattern

    def jacobian_array(self, t, y, yp, cj):
        """Return dF/dy + cj dF/dyp as a new (ny, ny) array."""
        jac = np.zeros((self.ny, self.ny))
        self.jacobian(t, np.ascontiguousarray(y, float), np.ascontiguousarray(yp, float), cj, jac)
        return jac

    def consistent_yp(self, t, y, iters=4, initial=False, tol=None):
        """Return yp with F(t, y, yp) = 0 by Newton's method on yp (F is linear in yp unless
        expressions use accelerations). dF/dyp is the difference of the iteration matrix at
        cj = 1 and cj = 0; large scenes use the sparse path. With motions and constraints y is
        made consistent too, in place, at the `initial` state with the motions' ic_disp and
        ic_vel, its changes noted for integr_tol `tol` (pysolver.build.consistent)."""
        if self.layout.lam or self.layout.turns:
            return start(self, t, y, tol) if initial else consistent(self, t, y)
        sparse = self.ny >= SPARSE_THRESHOLD
        if not sparse:                     # in C: a residual, two Jacobians, LU, per step
            if self._cyp is None:            # the arrays, and the C pointers into them
                work, piv = np.zeros(2 * self.ny * self.ny + self.ny), np.zeros(self.ny, np.int32)
                self._cyp = ((work, piv), ffi.from_buffer("double[]", work),
                             ffi.cast("int *", ffi.from_buffer(piv)))
            _, work, piv = self._cyp
            yp = np.zeros(self.ny)
            fb = ffi.from_buffer
            rc = lib.ps_consistent_yp(self.m, self.d, t, fb("double[]", np.ascontiguousarray(
                y, float)), fb("double[]", yp), work, piv, iters)
            if rc != lib.PS_OK and self.d.user_error:
                raise UserFailure(self.message)
            return yp if rc == lib.PS_OK else np.full(self.ny, np.nan)
        from scipy.sparse.linalg import spsolve  # large scenes: the sparse path
        yp = np.zeros(self.ny)
        for _ in range(iters):
            r = self.residual_array(t, y, yp)
            if not np.isfinite(r).all():     # d.bad_kind says where
                return np.full(self.ny, np.nan)
            J1, J0 = self.jacobian_csc_array(t, y, yp, 1.0), \
                self.jacobian_csc_array(t, y, yp, 0.0)
            if not (np.isfinite(J1.data).all() and np.isfinite(J0.data).all()):
                return np.full(self.ny, np.nan)
            dyp = spsolve((J1 - J0).tocsc(), -r)
            if not np.isfinite(dyp).all():         # singular dF/dyp: the caller says so
                return np.full(self.ny, np.nan)
            yp += dyp
            if np.max(np.abs(dyp)) <= 1e-14 * (1 + np.max(np.abs(yp))):
                break
        return yp


def follow(twin, kernel):
    """Give `twin` (a kernel of the same scene) the numbers pysolver.build.params may have
    changed in `kernel`: masses, inertias, marker positions, gravity and sweep parameters."""
    for key in ("body_mass", "body_inertia", "body_plane", "marker_pos"):
        twin.arrays[key][:] = kernel.arrays[key]
    for path, slot in kernel.params.items():
        if path in twin.params:
            twin.arrays["consts"][twin.params[path]] = kernel.arrays["consts"][slot]
    twin.m.gravity = list(kernel.m.gravity)
