"""Work-precision for IFToMM A05, the stiff flyball governor: pysolver against Exudyn, in one
process. Wall time against error.

Problem: decks/joints/iftomm_a05_flyball.xml (written by decks/joints/make_a05.py, whose
docstring gives the source of every number): a free shaft on a revolute about z, a 3 kg
slider on a translational joint along it, two rods (0.3 kg + a 5 kg ball each) hinged on
the shaft, the coupler rods replaced by spring-dampers K = 8e5 N/m, C = 4e4 N s/m (rest
length 0.5 m); every body turning at 2 pi rad/s at t = 0, gravity -9.81 z, 10 s.

Error: the slider centre height s(t) (pysolver: Post_Request 1 channel 0, DZ of the slider
on the shaft; Exudyn: the z position of the slider) against make_a05.py's reference() (an
independent minimal-coordinate model, SciPy Radau at rtol = atol = 1e-12, the table of
tests/test_iftomm_a05.py), computed here in-process on the same 0.25 s grid over 10 s (41
times); error = max over those times of |s - s_ref| in metres.

Solvers:
- pysolver: ``pysolver.load(deck).run(integr_tol=tol)`` for tol = 1e-4 ... 1e-10 (decades;
  IDA, variable order and step; output every 0.01 s as the deck says).
- Exudyn "bodies": the deck's model in the style of benchmarks/joint_references.py: five
  3-D rigid bodies (Euler parameters) from ``CreateRigidBody``, ``CreateRevoluteJoint`` x3,
  ``CreatePrismaticJoint``, two ``CreateSpringDamper``; generalized-alpha (index 3) at fixed
  steps h, Exudyn's defaults (spectral radius 0.9, modified Newton, relTol 1e-8). This is
  pysolver's formulation class (absolute coordinates and exact joints).
- Exudyn "kinematic tree": Exudyn's own model of this problem (stiffFlyballGovernorKT.py in
  Exudyn's examples: ``ObjectKinematicTree`` in four joint coordinates, no constraints),
  generalized-alpha at fixed h with the example's Newton settings
  (maxModifiedNewtonIterations = 2, jacobianConnectorDerivative = False; these halve its
  time here) but the default spectral radius 0.9 and relTol 1e-8 (the example's relTol 1e-6
  limits the error to ~1.7e-6 m at h = 1e-4).
Both Exudyn models write s every 0.01 s (sensor) as pysolver does; main() imports Exudyn's
``exudynFast`` build (no range checks, as its examples do; the JSON records which build ran).
Each Exudyn model's s(t) must approach the reference as h shrinks (second order): the
observed orders between successive h are printed and stored.

Timing: wall seconds in this process (time.perf_counter). pysolver: all of ``Model.run``,
after one untimed warm-up run at the loosest tolerance (it generates and compiles the
kernel), best of `repeat` runs. Exudyn: ``SolveDynamic`` only (model building not timed; a
fresh system per repeat), best of `exudyn_repeat`. A run that fails, stops early or returns
non-finite values is recorded as failed, never as a time. Headline: for each Exudyn point,
the fastest successful pysolver run whose error is at most Exudyn's, and the ratio Exudyn
time / pysolver time. No timing is asserted anywhere; the machine has 2 cores and may be
shared, so the load average is recorded with every row.

Run from the checkout root: ``python benchmarks/flyball.py [--quick] [--repeat 5]
[--exudyn-repeat 2] [--out PATH]``. The full mode takes about 75 s on this 2-core machine
(the Exudyn runs at h = 1e-4 and 5e-5 dominate); ``--quick`` (about 5 s with the kernel
cached, 11 s when it compiles) runs pysolver at 1e-4, 1e-7, 1e-10 and both Exudyn models at
h = 1e-3 only. Writes benchmarks/data/flyball_work_precision.json (every number, the
machine, the versions and the commit pysolver was imported from) and prints the tables.
"""
import argparse
import math
import os
import pathlib
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
DECKS = ROOT / "decks" / "joints"
sys.path.insert(0, str(DECKS))

import make_a05 as a05  # noqa: E402 - decks/joints/ is put on the path just above
import provenance  # noqa: E402 - benchmarks/ is on the path

import pysolver  # noqa: E402

PYSOLVER_ROOT = pathlib.Path(pysolver.__file__).resolve().parent.parent
DECK = DECKS / "iftomm_a05_flyball.xml"
OUT = HERE / "data" / "flyball_work_precision.json"

T_END = 10.0
OUT_DT = 0.01                                  # the deck's print_interval, Exudyn's sensors
REF_TIMES = np.arange(0.0, T_END + 1e-9, 0.25)  # the grid of tests/test_iftomm_a05.py

#: integr_tol values and Exudyn steps h, full mode / --quick
TOLS = ((1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10), (1e-4, 1e-7, 1e-10))
BODIES_H = ((1e-3, 5e-4, 2e-4, 1e-4, 5e-5), (1e-3,))
TREE_H = ((1e-3, 5e-4, 2e-4, 1e-4, 5e-5), (1e-3,))


# ---------------------------------------------------------------------------------------
# reference
def reference(check=False):
    """s_ref at REF_TIMES from make_a05.reference() (rtol = atol = 1e-12); with `check`, also
    the run at 1e-11 and the largest difference between them."""
    t0 = time.perf_counter()
    s = a05.reference(REF_TIMES)[0]
    out = dict(times=[float(t) for t in REF_TIMES], s=[float(v) for v in s],
               how="decks/joints/make_a05.py reference(): minimal coordinates (s, theta1, "
                   "theta2), shaft momentum conserved (Routh), SciPy Radau rtol = atol = 1e-12",
               wall_s=time.perf_counter() - t0)
    if check:
        s2 = a05.reference(REF_TIMES, 1e-11, 1e-11)[0]
        out["max_diff_to_rtol_1e-11_m"] = float(np.abs(s - s2).max())
    return np.asarray(s), out


def s_error(t, s, s_ref):
    """max |s - s_ref| over REF_TIMES, picking the output rows at those times; None if the
    output does not reach the end or is not finite."""
    t = np.asarray(t)
    if not len(t) or t[-1] < T_END - 1e-9:
        return None
    rows = np.searchsorted(t, REF_TIMES - 1e-7)
    if np.any(rows >= len(t)) or not np.allclose(t[rows], REF_TIMES, rtol=0, atol=1e-7):
        raise RuntimeError("the run's output times are not the reference's")
    d = np.abs(np.asarray(s)[rows] - s_ref)
    return float(d.max()) if np.all(np.isfinite(d)) else None


# ---------------------------------------------------------------------------------------
# pysolver
def pysolver_sweep(tols, repeat, s_ref):
    """One row per tolerance. The first run (at the loosest tolerance) compiles the kernel
    and is not timed."""
    model = pysolver.load(DECK)
    t0 = time.perf_counter()
    warm = model.run(integr_tol=max(tols))
    warm_s = time.perf_counter() - t0
    rows = []
    for tol in tols:
        best, res = math.inf, None
        for _ in range(repeat):
            t0 = time.perf_counter()
            res = model.run(integr_tol=tol)
            best = min(best, time.perf_counter() - t0)
        err = s_error(res.t, res.request(1)[:, 0], s_ref) if len(res.t) else None
        ok = bool(res.success) and err is not None
        rows.append(dict(method="pysolver", integr_tol=tol, repeat=repeat,
                         steps=int(res.stats["steps"]), nres=int(res.stats["nres"]),
                         njac=int(res.stats["njac"]), nfail=int(res.stats["nfail"]),
                         wall_s=best if ok else None,
                         wall_s_until_failure=None if ok else best,
                         max_err_m=err if ok else None, success=ok, message=res.message,
                         reached_t=float(res.t[-1]) if len(res.t) else None,
                         load_1min=os.getloadavg()[0]))
        print(f"  pysolver tol {tol:.0e}: {provenance.fmt_row(rows[-1])}", flush=True)
    return rows, dict(integr_tol=max(tols), wall_s_including_compile=warm_s,
                      success=bool(warm.success), timing=provenance.plain(warm.timing))


# ---------------------------------------------------------------------------------------
# Exudyn
def _settings(h):
    import exudyn as exu
    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = int(round(T_END / h))
    s.timeIntegration.endTime = T_END
    s.timeIntegration.verboseMode = 0
    s.show.computationTime = False
    s.show.statistics = False
    s.solution.file.write = False
    s.solution.sensors.writePeriod = OUT_DT
    return s


def _rod_inertia():
    """Rod (1 x 0.01 x 0.01 m, 3000 kg/m^3) plus the 5 kg ball at its end, about the hinge,
    x along the rod (as Exudyn's example writes it)."""
    import exudyn.utilities as eu
    return (eu.InertiaCuboid(density=a05.RHO, sideLengths=[a05.L_ROD, a05.W, a05.W])
            .Translated([a05.L_ROD / 2, 0, 0])
            + eu.InertiaMassPoint(mass=a05.M_BALL).Translated([a05.L_ROD, 0, 0]))


#: rod directions at t = 0: x along the rod, 30 deg below the horizontal, +x and -x side
def _rod_rotations():
    import exudyn.utilities as eu
    return ((1, eu.RotationMatrixY(a05.ALPHA)), (-1, eu.RotationMatrixY(math.pi - a05.ALPHA)))


def exudyn_bodies(h):
    """The deck's model from 3-D rigid bodies and joints; returns (mbs, sensor, settings)."""
    import exudyn as exu
    import exudyn.utilities as eu
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    g = [0, 0, -a05.G]
    w = np.array([0.0, 0.0, a05.OMEGA0])
    ground = mbs.CreateGround()
    shaft = mbs.CreateRigidBody(
        inertia=eu.InertiaCuboid(density=a05.RHO, sideLengths=[a05.W, a05.W, 1.0]),
        referencePosition=[0, 0, 0.5], initialAngularVelocity=w, gravity=g)
    slider = mbs.CreateRigidBody(
        inertia=eu.InertiaCuboid(density=a05.RHO, sideLengths=[0.1, 0.1, 0.1]),
        referencePosition=[0, 0, a05.S0], initialAngularVelocity=w, gravity=g)
    for sign, rot in _rod_rotations():
        hinge = np.array([sign * a05.A, 0.0, a05.H])
        rod = mbs.CreateRigidBody(inertia=_rod_inertia(), referencePosition=hinge,
                                  referenceRotationMatrix=rot,
                                  initialVelocity=np.cross(w, hinge),
                                  initialAngularVelocity=w, gravity=g)
        mbs.CreateRevoluteJoint(itemNumbers=[shaft, rod], position=hinge, axis=[0, 1, 0],
                                useGlobalFrame=True)
        mbs.CreateSpringDamper(itemNumbers=[slider, rod], localPosition0=[sign * a05.A, 0, 0],
                               localPosition1=[a05.L_SPRING_AT, 0, 0],
                               referenceLength=a05.L0, stiffness=a05.K, damping=a05.C)
    # created after the rods: with the shaft's two joints created first, Exudyn's default
    # dense solver (EXUdense) took twice as long here at the same Newton counts
    # (EigenSparse did not care); the faster order is the one timed
    mbs.CreateRevoluteJoint(itemNumbers=[ground, shaft], position=[0, 0, 0], axis=[0, 0, 1],
                            useGlobalFrame=True)
    mbs.CreatePrismaticJoint(itemNumbers=[shaft, slider], position=[0, 0, a05.S0],
                             axis=[0, 0, 1], useGlobalFrame=True)
    sens = mbs.AddSensor(eu.SensorBody(bodyNumber=slider, storeInternal=True,
                                       outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    return mbs, sens, _settings(h)


def exudyn_tree(h):
    """Exudyn's stiffFlyballGovernorKT.py model: one kinematic tree [shaft (RevoluteZ),
    slider (PrismaticZ), rod 1, rod 2 (RevoluteY)], the couplers as SpringDampers between
    kinematic-tree markers; returns (mbs, sensor, settings)."""
    import exudyn as exu
    import exudyn.itemInterface as ei
    import exudyn.utilities as eu
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    node = mbs.AddNode(ei.NodeGenericODE2(referenceCoordinates=[0.0] * 4,
                                          initialCoordinates=[0.0] * 4,
                                          initialCoordinates_t=[a05.OMEGA0, 0, 0, 0],
                                          numberOfODE2Coordinates=4))
    (_, rot1), (_, rot2) = _rod_rotations()
    inertias = [eu.InertiaCuboid(density=a05.RHO, sideLengths=[a05.W, a05.W, 1.0]),
                eu.InertiaCuboid(density=a05.RHO, sideLengths=[0.1, 0.1, 0.1]),
                _rod_inertia(), _rod_inertia()]
    offsets = [[0, 0, 0.5], [0, 0, a05.S0 - 0.5], [a05.A, 0, a05.H - 0.5],
               [-a05.A, 0, a05.H - 0.5]]
    rots = [np.eye(3), np.eye(3), rot1, rot2]
    transforms, joint_offsets = exu.Matrix3DList(), exu.Vector3DList()
    coms, inertias_com = exu.Vector3DList(), exu.Matrix3DList()
    for inertia, off, rot in zip(inertias, offsets, rots):
        transforms.Append(rot)
        joint_offsets.Append(off)
        coms.Append(inertia.COM())
        inertias_com.Append(inertia.InertiaCOM())
    jt = exu.JointType
    tree = mbs.AddObject(ei.ObjectKinematicTree(
        nodeNumber=node, jointTypes=[jt.RevoluteZ, jt.PrismaticZ, jt.RevoluteY, jt.RevoluteY],
        linkParents=[-1, 0, 0, 0], jointTransformations=transforms, jointOffsets=joint_offsets,
        linkInertiasCOM=inertias_com, linkCOMs=coms, linkMasses=[i.Mass() for i in inertias],
        baseOffset=[0, 0, 0], gravity=[0, 0, -a05.G]))
    for link, sign in ((2, 1), (3, -1)):
        m0 = mbs.AddMarker(ei.MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=1,
                                                       localPosition=[sign * a05.A, 0, 0]))
        m1 = mbs.AddMarker(ei.MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=link,
                                                       localPosition=[a05.L_SPRING_AT, 0, 0]))
        mbs.AddObject(ei.SpringDamper(markerNumbers=[m0, m1], stiffness=a05.K, damping=a05.C,
                                      referenceLength=a05.L0))
    sens = mbs.AddSensor(ei.SensorKinematicTree(
        objectNumber=tree, linkNumber=1, localPosition=[0, 0, 0], storeInternal=True,
        outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    s = _settings(h)
    s.timeIntegration.newton.maxModifiedNewtonIterations = 2
    s.timeIntegration.newton.numericalDifferentiation.jacobianConnectorDerivative = False
    return mbs, sens, s


EXUDYN_MODELS = {
    "bodies": (exudyn_bodies, "3-D rigid bodies (Euler parameters), CreateRevoluteJoint x3, "
               "CreatePrismaticJoint (the shaft's joints created after the rods, the faster "
               "order for EXUdense), CreateSpringDamper x2; generalized-alpha index 3, "
               "Exudyn defaults (spectral radius 0.9, modified Newton, relTol 1e-8, "
               "EXUdense)"),
    "kinematic_tree": (exudyn_tree, "Exudyn's stiffFlyballGovernorKT.py model: "
                       "ObjectKinematicTree in 4 joint coordinates, SpringDamper x2 on "
                       "MarkerKinematicTreeRigid; generalized-alpha, spectral radius 0.9, "
                       "relTol 1e-8, the example's maxModifiedNewtonIterations = 2 and "
                       "jacobianConnectorDerivative = False"),
}


def exudyn_row(name, h, repeat, s_ref):
    """Best SolveDynamic wall time of `repeat` fresh systems; failed if any run raises, stops
    short of 10 s or returns non-finite s."""
    build = EXUDYN_MODELS[name][0]
    best, ok, msg, err, reached, stats = math.inf, True, "", None, None, {}
    for _ in range(repeat):
        mbs, sens, settings = build(h)
        t0 = time.perf_counter()
        try:
            mbs.SolveDynamic(settings)
        except Exception as e:               # noqa: BLE001 - report any solver failure
            ok, msg = False, str(e).splitlines()[0][:200] if str(e) else type(e).__name__
        wall = time.perf_counter() - t0
        best = min(best, wall)
        data = mbs.GetSensorStoredData(sens)
        reached = float(data[-1, 0]) if len(data) else None
        try:
            it = mbs.sys["dynamicSolver"].it
            stats = dict(newton_iterations=int(it.newtonStepsCount),
                         jacobians=int(it.newtonJacobiCount))
        except (KeyError, AttributeError):
            stats = {}
        if ok:
            err = s_error(data[:, 0], data[:, 3], s_ref) if len(data) else None
            if err is None:
                ok, msg = False, "stopped short of the end time or non-finite s"
        if not ok:
            break
    row = dict(method=f"Exudyn {name}", model=name, h=h, steps=int(round(T_END / h)),
               repeat=repeat, **stats, wall_s=best if ok else None,
               wall_s_until_failure=None if ok else best, max_err_m=err if ok else None,
               success=ok, message=msg, reached_t=reached, load_1min=os.getloadavg()[0])
    print(f"  Exudyn {name} h {h:.0e}: {provenance.fmt_row(row)}", flush=True)
    return row


def convergence(rows):
    """Observed order of the error between successive successful h."""
    ok = [r for r in rows if r["success"]]
    return [dict(h=(a["h"], b["h"]), err=(a["max_err_m"], b["max_err_m"]),
                 order=math.log(a["max_err_m"] / b["max_err_m"]) / math.log(a["h"] / b["h"]))
            for a, b in zip(ok, ok[1:])]


# ---------------------------------------------------------------------------------------
# report
def headline(py_rows, ex_rows):
    """Each Exudyn point matched with the fastest pysolver run at equal or smaller error."""
    return provenance.headline(py_rows, ex_rows, exudyn_model="model")


def print_table(rows):
    print("\nIFToMM A05 stiff flyball governor, 10 s: max |s - s_ref| over 41 times")
    print(f"{'method':>22} {'setting':>10} {'steps':>8} {'res|Newton':>10} {'wall s':>9} "
          f"{'max error m':>12}")
    for r in rows:
        setting = (f"tol {r['integr_tol']:.0e}" if r["method"] == "pysolver"
                   else f"h {r['h']:.0e}")
        wall = "failed" if r["wall_s"] is None else f"{r['wall_s']:.4f}"
        err = "-" if r["max_err_m"] is None else f"{r['max_err_m']:.2e}"
        nit = r.get("newton_iterations", r.get("nres"))
        nit = "-" if nit is None else f"{nit:,}"
        print(f"{r['method']:>22} {setting:>10} {r['steps']:>8,} {nit:>10} {wall:>9} "
              f"{err:>12}")
        if not r["success"]:
            print(f"{'':>23}failed: {r['message']} (reached t = {r.get('reached_t')})")
    print("(res|Newton: pysolver residual evaluations, Exudyn Newton iterations)")


def print_headline(lines):
    print("\nFastest pysolver run at equal or smaller error than each Exudyn point")
    for h in lines:
        ex = (f"Exudyn {h['exudyn_model']} h {h['exudyn_h']:.0e}: {h['exudyn_wall_s']:.4f} s, "
              f"{h['exudyn_max_err_m']:.2e} m")
        if h["ratio"] is None:
            print(f"  {ex}; no pysolver run reaches that error")
        else:
            print(f"  {ex}; pysolver tol {h['pysolver_integr_tol']:.0e}: "
                  f"{h['pysolver_wall_s']:.4f} s, {h['pysolver_max_err_m']:.2e} m -> "
                  f"{provenance.speed(h['ratio'])}")


def print_convergence(conv):
    print("\nExudyn models against the reference as h shrinks (observed order)")
    for name, pairs in conv.items():
        for c in pairs:
            print(f"  {name}: h {c['h'][0]:.0e} -> {c['h'][1]:.0e}: {c['err'][0]:.2e} -> "
                  f"{c['err'][1]:.2e} m, order {c['order']:.2f}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="pysolver at 1e-4, 1e-7, 1e-10; both Exudyn models at h = 1e-3 only")
    ap.add_argument("--repeat", type=int, default=None,
                    help="pysolver runs per tolerance, best taken (default 5, --quick 3)")
    ap.add_argument("--exudyn-repeat", type=int, default=None,
                    help="Exudyn solves per step size, best taken (default 2, --quick 1)")
    ap.add_argument("--out", default=str(OUT))
    args = ap.parse_args(argv)
    q = int(args.quick)
    repeat = args.repeat or (3 if args.quick else 5)
    ex_repeat = args.exudyn_repeat or (1 if args.quick else 2)
    if "exudyn" not in sys.modules:
        sys.exudynFast = True                # Exudyn's build without range checks
    t_start = time.perf_counter()
    out = dict(generated_by="benchmarks/flyball.py" + (" --quick" if args.quick else ""),
               machine=provenance.machine(pysolver, PYSOLVER_ROOT),
               problem=dict(deck=str(DECK.relative_to(ROOT)), t_end=T_END, output_dt=OUT_DT,
                            quantity="s: slider centre height (m)",
                            error="max over the reference times of |s - s_ref| (m)"),
               method=("one process; pysolver: first run (compiles the kernel) untimed, then "
                       f"best of {repeat} Model.run per tolerance; Exudyn: generalized-alpha "
                       f"at fixed step h, best of {ex_repeat} SolveDynamic calls (fresh "
                       "system each, building not timed); wall seconds; failed runs are "
                       "recorded as failed"),
               exudyn_models={k: v[1] for k, v in EXUDYN_MODELS.items()})

    print("reference: make_a05.py reference() on the 0.25 s grid", flush=True)
    s_ref, out["reference"] = reference(check=not args.quick)

    print("pysolver: integr_tol sweep", flush=True)
    py, warm = pysolver_sweep(TOLS[q], repeat, s_ref)
    out["pysolver"], out["pysolver_warmup"] = py, warm
    provenance.save(out, args.out)                      # so far, in case the run is stopped

    out["exudyn"], conv = {}, {}
    for name, hs in (("bodies", BODIES_H[q]), ("kinematic_tree", TREE_H[q])):
        print(f"Exudyn {name}: step sweep", flush=True)
        out["exudyn"][name] = [exudyn_row(name, h, ex_repeat, s_ref) for h in hs]
        conv[name] = convergence(out["exudyn"][name])
        provenance.save(out, args.out)
    out["exudyn_convergence"] = conv
    ex_rows = [r for rows in out["exudyn"].values() for r in rows]
    out["headline"] = headline(py, ex_rows)

    print_table(py + ex_rows)
    print_headline(out["headline"])
    print_convergence(conv)
    provenance.finish(out, args.out, t_start, PYSOLVER_ROOT)


if __name__ == "__main__":
    main()
