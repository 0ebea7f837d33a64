"""The kernel's iteration matrix against central finite differences of its residual."""
import numpy as np
import pytest

import pysolver

from helpers import TEST_DECKS, fd_iteration_matrix

SCENES = [TEST_DECKS / "all_functions.xml", TEST_DECKS / "all_joints.xml",
          TEST_DECKS / "gcon.xml", TEST_DECKS / "couplers.xml", TEST_DECKS / "lead_joints.xml",
          TEST_DECKS / "springs.xml", TEST_DECKS / "bushing.xml", TEST_DECKS / "nonholonomic.xml",
          TEST_DECKS / "planar_fourbar.xml", TEST_DECKS / "field_beam.xml"] + [
    f"{name}.xml" for name in ("catenary_bead", "particle_above_line", "particle_between_lines",
                               "torque_free_spin")]


def _path(decks, scene):
    return scene if not isinstance(scene, str) else decks / scene


@pytest.mark.parametrize("kind", ["generated", "tapes"])
@pytest.mark.parametrize("scene", SCENES, ids=lambda s: str(s).split("/")[-1])
def test_jacobian_matches_central_differences(decks, scene, kind):
    """On both kernels: the generated C (symbolic derivatives) and the tapes (hyper-duals)."""
    kernel = pysolver.load(_path(decks, scene)).compile(kind).kernel
    assert kernel.codegen["kernel"] == kind
    y0 = kernel.layout.initial_state()
    rng = np.random.default_rng(42)
    for trial in range(4):
        y = y0 + 0.05 * rng.normal(size=kernel.ny)
        if "particle" in str(scene):
            y = y0 * 0 + rng.normal(size=kernel.ny) * [1, 1, 1, 3, 3, 3]
            y[2] = 1.0 + y[0] + 0.3 * (trial - 1.5)  # across the smoothing band of the penalty
        yp = rng.normal(size=kernel.ny)
        cj = 10.0 ** rng.uniform(-1, 3)
        J = kernel.jacobian_array(0.37, y, yp, cj)
        Jfd = fd_iteration_matrix(kernel, 0.37, y, yp, cj)
        scale = np.abs(J).max()
        assert np.all(np.abs(J - Jfd) <= 1e-6 * (np.abs(Jfd) + 1e-3 * scale)), \
            np.abs(J - Jfd).max() / scale


@pytest.mark.parametrize("kind", ["generated", "tapes"])
def test_jacobian_has_no_entries_outside_the_coupling(kind):
    """Bodies that no force couples have an exactly zero off-diagonal block."""
    deck = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="2" body_id="2" pos_z="1"/><Reference_Marker id="3" body_id="3" pos_x="1"/>
      <Body_Point id="2" cg_id="2" mass="1"/><Body_Point id="3" cg_id="3" mass="1"/>
      <Force_Penalty id="1" expr="DZ(2) - 1" penalty="10" penalty1="1"/>
      </Model></MotionSolve>"""
    k = pysolver.loads(deck).compile(kind).kernel
    J = k.jacobian_array(0.0, np.arange(12.0), np.ones(12), 2.0)
    assert np.all(J[:6, 6:] == 0) and np.all(J[6:, :6] == 0)


def test_ida_uses_the_kernel_jacobian(decks):
    """Every Jacobian IDA forms is a kernel call: the kernel's Jacobian count exceeds IDA's by
    exactly the initial-condition calls, which are all a difference-quotient run makes."""
    model = pysolver.load(decks / "particle_between_lines.xml")
    exact = model.run(nonlin_conv_coef=0.33)      # IDA's own Newton test, as in the dq run
    dq = model.run(jacobian="dq")
    ic_jac = dq.stats["njac"]                 # consistent yp only: IDA never calls the kernel
    assert 0 < ic_jac <= 8 and dq.stats["ida_njev"] > 0
    assert exact.stats["ida_njev"] > 0
    assert exact.stats["njac"] - exact.stats["ida_njev"] == ic_jac
    assert 0 < exact.stats["nres"] - exact.stats["ida_nfev"] <= ic_jac
    # difference quotients cost ny residuals per Jacobian that the exact path does not pay
    assert dq.stats["nres"] > exact.stats["nres"] + 6 * (dq.stats["ida_njev"] - 10)
