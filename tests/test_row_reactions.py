"""Output rows take their accelerations and reactions exact at their positions and velocities
(ps_row_exact, options.reactions = "exact"): IDA's error test leaves the reactions out and
holds the accelerations only to about the tolerance over a step, so a driven rod's torque
carried 2 % of noise at integr_tol 1e-3 and 0.17 % at 1e-6 (trial 43)."""
import numpy as np
import pytest

import pysolver

# a 2 kg rod on a revolute about z at the origin, its centre of mass 0.5 m along x, driven by
# theta = sin(3 t) under gravity -y: the driving torque is (Icm + m a^2) theta'' + m g a cos
ROD = """from pysolver.msolve import *
model = Model()
Accgrav(jgrav=-9.81)
ground = Part(ground=True)
o = Marker(body=ground)
rod = Part(mass=2.0, ip=[0.1, 0.1, 0.1])
rod.cm = Marker(body=rod, qp=[0.5, 0, 0])
pin = Marker(body=rod)
hinge = Joint(type="REVOLUTE", i=pin, j=o)
Motion(joint=hinge, jtype="ROTATION", function="SIN(3*TIME)")
Request(f1=f"WDTZ({rod.cm.id})", f2=f"ACCX({rod.cm.id})", f3=f"ACCY({rod.cm.id})")
model.simulate(type="DYNAMICS", end=2, dtout=0.01)
"""


def _torque(t):
    th = np.sin(3 * t)
    return (0.1 + 2 * 0.25) * (-9 * th) + 2 * 9.81 * 0.5 * np.cos(th)


@pytest.mark.parametrize("tol, bound", [(1e-3, 1e-2), (1e-6, 1e-5), (1e-9, 1e-8)])
def test_a_driven_rod_s_torque_and_accelerations_are_the_closed_form(tol, bound):
    """The motion's torque within `bound` of its largest value at every row (measured 3e-3,
    4e-6 and 3e-9: the state's own error at the tolerance), and the centre of mass's
    accelerations those of the prescribed rotation, on both kernels alike."""
    model = pysolver.loads(ROD, fmt="py")
    for kernel in ("tapes", "generated"):
        res = model.run(integr_tol=tol, kernel=kernel)
        assert res.success, res.message
        t, T = res.t, _torque(res.t)
        assert np.abs(res.motion(1) - T).max() <= bound * np.abs(T).max()
        th, w, a = np.sin(3 * t), 3 * np.cos(3 * t), -9 * np.sin(3 * t)
        want = np.column_stack([a, -0.5 * (a * np.sin(th) + w ** 2 * np.cos(th)),
                                0.5 * (a * np.cos(th) - w ** 2 * np.sin(th))])
        assert np.abs(res.request(1)[:, :3] - want).max() <= bound * np.abs(want).max()


def test_the_integrator_s_reactions_on_request_keep_the_same_trajectory():
    """reactions="integrator" gives IDA's corrector values (the rows' reactions and
    accelerations differ) on the very same positions and velocities: the option changes what
    the rows report, not the run."""
    model = pysolver.loads(ROD, fmt="py")
    exact, raw = model.run(), model.run(reactions="integrator")
    assert exact.success and raw.success
    assert exact.stats["steps"] == raw.stats["steps"]
    moving = [i for i, n in enumerate(exact.state_names) if n.startswith("body")]
    np.testing.assert_array_equal(exact.y[:, moving], raw.y[:, moving])
    assert np.abs(exact.motion(1) - raw.motion(1)).max() > 1e-6
    with pytest.raises(ValueError, match="reactions must be 'exact', 'integrator'"):
        model.run(reactions="corrector")
