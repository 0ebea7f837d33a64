"""The IFToMM multibody benchmarks with exact joints (decks/joints/): A02 N-four-bar through
its singular configurations, A03 Andrews' squeezing mechanism against the Test Set for IVP
solvers, A04 Bricard's overconstrained mechanism. References: benchmarks/data/
joint_references.json (how each was made and checked: benchmarks/data/README-joints.md)."""
import json
import re
import sys

import numpy as np
import pytest

import pysolver

from helpers import ROOT

JOINTS = ROOT / "decks" / "joints"
REFERENCE = json.loads((ROOT / "benchmarks" / "data" / "joint_references.json").read_text())[
    "problems"]


@pytest.mark.parametrize("planar", ["off", "auto"])
def test_a02_four_bar_passes_its_singular_configurations_on_the_branch(monkeypatch, planar):
    """N = 40 (81 links, 121 revolutes), the first 2.5 s, in 3-D (PYSOLVER_PLANAR=off: 120
    redundant equations removed, 2,023 unknowns) and as the planar scene it is (970 unknowns:
    each revolute's 3 out-of-plane equations left out, none redundant in the plane):
    the mechanism passes the horizontal, where its constraints lose rank, at 0.72 s and
    1.24 s. Before the first crossing point B0 follows the exact 1-DOF solution of the
    parallelogram branch to the tolerance's order (below 2e-7 m at integr_tol 1e-8 and 1e-9;
    measured up to 8.1e-8 m). Each crossing turns rounding-size differences into an error
    that the phase of this motion, close to its separatrix, then amplifies: a 1 % change of
    the tolerance, or another factorization of the same matrices (SuperLU_MT), moves the
    error at 2.5 s between 9.4e-8 and 1.3e-5 m at 1e-8 and between 2.5e-7 and 1.5e-6 m at
    1e-9 (docs/numerics.md, "Constraints"). Over the 2.5 s the error stays below 1e-4 m and
    2e-5 m (a solver that switches branch is off by metres), in fewer than 3,000 steps
    (measured 1,049-1,182 and 1,495-1,659; before the position rows' compliance was 1e-9 s,
    1e-9 took 87,721 steps to 1 s). The planar scene's error before the first crossing at
    1e-8 is below 3e-7 m instead (measured 4.4e-8..1.6e-7 m at 18 tolerances within 3 % of
    1e-8; its error at 2.5 s 4.8e-7..1.1e-5 m; 1,010-1,144 steps; at 1e-9 2.7e-9..1.7e-8 m
    before, 4.6e-8..4.3e-7 m at 2.5 s, 1,413-1,547 steps)."""
    monkeypatch.setenv("PYSOLVER_PLANAR", planar)
    ref = REFERENCE["iftomm_a02_fourbar"]
    assert ref["horizontal_crossing_times_s"][0] > 0.7
    assert ref["horizontal_crossing_times_s"][1] < 2.5
    text = re.sub(r'end_time="[^"]*"', 'end_time="2.5"',
                  (JOINTS / "iftomm_a02_fourbar.xml").read_text())
    model = pysolver.loads(text)
    times = np.array(ref["times"])
    n = np.searchsorted(times, 2.5, side="right")
    before = times[:n] < 0.7
    note = ("redundant constraints removed (120)" if planar == "off" else
            "planar scene: 81 bodies integrated in (x, y, rz)")
    assert model.compile().kernel.ny == (2023 if planar == "off" else 970)
    for tol, bound in ((1e-8, 1e-4), (1e-9, 2e-5)):
        res = model.run(integr_tol=tol)
        assert res.success, res.message
        assert any(note in line for line in res.log)
        rows = np.searchsorted(res.t, times[:n])
        assert np.allclose(res.t[rows], times[:n], rtol=0, atol=1e-12)
        b0 = res.request(1)[rows]
        err = np.hypot(b0[:, 0] - ref["B0_x"][:n], b0[:, 1] - ref["B0_y"][:n])
        assert err[before].max() < (2e-7 if planar == "off" or tol < 5e-9 else 3e-7)
        assert err.max() < bound
        assert res.stats["steps"] < 3000


@pytest.mark.parametrize("planar", ["off", "auto"])
def test_a03_andrews_mechanism_meets_the_test_set(monkeypatch, planar):
    """Seven bodies, ten revolutes (9 redundant equations in 3-D: 173 unknowns; as the
    planar scene it is, with its drive torque and spring in the plane, 82), 0.03 s. The Test
    Set's error measure (benchmarks/andrews.py) falls with the tolerance: below 2e-6 at
    integr_tol 1e-9 and 2e-7 at 1e-10 (measured 1.10e-6 and 1.05e-7 in 3-D, 1.12e-6 and
    1.10e-7 planar; the penalty-joint version reached 8.4e-6)."""
    monkeypatch.setenv("PYSOLVER_PLANAR", planar)
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        import andrews
    finally:
        sys.path.pop(0)
    model = pysolver.load(JOINTS / "iftomm_a03_andrews.xml")
    assert model.compile().kernel.ny == (173 if planar == "off" else 82)
    errors = []
    for tol in (1e-9, 1e-10):
        res = model.run(integr_tol=tol)
        assert res.success, res.message
        errors.append(andrews.error(res))
    assert errors[0] < 2e-6 and errors[1] < 2e-7
    assert errors[1] < errors[0] / 5


def test_a04_bricard_keeps_its_loop_and_its_energy():
    """Five rods, six revolutes, one redundant equation (removed and named in the log), from
    rest under gravity for 10 s. At integr_tol 1e-10 point P3 within 1e-8 m of the reference
    (measured 1.1e-9) and the energy (a request channel) constant within 1e-7 J (1.1e-8;
    about 29 J of potential energy turn into motion and back)."""
    ref = REFERENCE["iftomm_a04_bricard"]
    res = pysolver.load(JOINTS / "iftomm_a04_bricard.xml").run(integr_tol=1e-10)
    assert res.success, res.message
    assert any("redundant constraints removed (1)" in line for line in res.log), res.log
    rows = np.searchsorted(res.t, ref["times"])
    q = res.request(1)
    p3 = np.column_stack([ref["P3_x"], ref["P3_y"], ref["P3_z"]])
    assert np.linalg.norm(q[rows, :3] - p3, axis=1).max() < 1e-8
    assert np.abs(q[:, 3] - q[0, 3]).max() < 1e-7
    assert np.ptp(q[:, 0]) > 1.5                     # it swings: x from 1 to about -1
