"""Static and quasi-static equilibrium: FIM_S, MKEAM, FIM_D (seed 004)."""
import math
import re

import numpy as np
import pytest

import pysolver

from scenes import rest_penetration


def load(decks, name, **replace):
    text = (decks / name).read_text()
    for old, new in replace.items():
        text = text.replace(old, new)
    return pysolver.loads(text)


def with_method(decks, name, method, extra=""):
    return load(decks, name, **{'method="FIM_S"': f'method="{method}"{extra}'})


@pytest.mark.parametrize("method,max_iter", [("FIM_S", 40), ("MKEAM", 10)])
def test_seed3_static_from_100_mm_away(decks, method, max_iter):
    model = with_method(decks, "static_seed3.xml", method)
    start = model.markers[10].pos
    g = rest_penetration(1e4, 9.81, 1.0)
    assert np.hypot(start[0], start[2] - (1 - g)) == pytest.approx(100.0, abs=0.1)
    res = model.run()
    assert res.success, res.message
    st = res.statics[0]
    assert st.success and st.iterations <= max_iter and st.imbalance < 1e-8
    x, z = res.request(1)[0, :2]
    assert abs(x) < 1e-8 and abs(z - (1 - g)) < 1e-8
    # the transient that follows starts at rest in equilibrium and stays there
    np.testing.assert_allclose(res.request(1)[:, 1], 1 - g, atol=1e-8)
    assert st.method == ("MKEAM+FIM_S" if method == "MKEAM" else "FIM_S")


def test_pendulum_fim_s_finds_the_top_and_mkeam_the_bottom(decks):
    top = with_method(decks, "static_pendulum.xml", "FIM_S").run()
    bottom = with_method(decks, "static_pendulum.xml", "MKEAM").run()
    assert top.success and bottom.success
    sag = 9.81 / 1e6            # the joint carries the weight: m g / penalty
    np.testing.assert_allclose(top.request(1)[0, :4], [0, 0, 0.5 - sag, sag], atol=1e-9)
    np.testing.assert_allclose(bottom.request(1)[0, :4], [0, 0, -0.5 - sag, sag], atol=1e-9)
    assert top.statics[0].iterations <= 20 and bottom.statics[0].iterations <= 10
    # the equilibria are those of rotation increments: unit Euler parameters
    e = top.y[0, 3:7]
    assert abs(np.linalg.norm(e) - 1) < 1e-14
    # stiffness: upright is unstable (a negative eigenvalue), hanging is stable
    k_top = np.linalg.eigvalsh(np.linalg.inv(top.compliance) + np.linalg.inv(top.compliance).T)
    k_bot = np.linalg.eigvalsh(np.linalg.inv(bottom.compliance) + np.linalg.inv(bottom.compliance).T)
    assert k_top.min() < -1 and k_bot.min() > -1e-3


@pytest.mark.parametrize("stability", ["1e-10", "1e-4", "1e-1"])
def test_neutral_equilibrium_needs_stability_and_does_not_depend_on_it(decks, stability):
    res = load(decks, "static_neutral_floor.xml",
               **{'stability="1e-10"': f'stability="{stability}"'}).run()
    assert res.success
    g = rest_penetration(0.5e5, 2 * 9.81, 1e-3)   # one penalty: k g S = m g
    x, y, z, f = res.request(1)[0, :4]
    assert (x, y) == (0.3, -0.2)
    assert abs(z + g) < 1e-12 and f == pytest.approx(-2 * 9.81, abs=1e-9)


def test_neutral_equilibrium_is_singular_without_stability(decks):
    res = load(decks, "static_neutral_floor.xml", **{'stability="1e-10"': 'stability="0"'}).run()
    assert not res.success and res.status == -300
    # nothing moved: the best point is the start, the 2 kg ball's weight (19.6 N) unbalanced
    assert res.message == (
        "static analysis at t = 0: FIM_S did not converge: plain Newton met a singular "
        "stiffness matrix at iteration 1, then Newton with step halving met a singular "
        "stiffness matrix at iteration 1 (a neutral equilibrium?): set Param_Static stability "
        "> 0; the best imbalance reached 19.6 (max_imbalance 1e-09) with increment or "
        "constraint violation 0")
    assert res.statics[0].iterations == 0


def test_non_convergence_reports_both_passes_and_the_best_imbalance(decks):
    """max_num_iter 3 from 100 mm away: both passes use their three iterations, each cut to
    tlimit's 20 mm; the best point is the lowest imbalance either reached, not the last."""
    res = with_method(decks, "static_seed3.xml", "FIM_S", ' max_num_iter="3"').run()
    assert not res.success and res.status == -300
    st = res.statics[0]
    assert st.iterations == 6 and st.imbalance <= 9.81
    assert res.message == (
        "static analysis at t = 0: FIM_S did not converge: plain Newton used all 3 iterations "
        "(max_num_iter), then Newton with step halving used all 3 iterations (max_num_iter) "
        "(tlimit cut 3 of the 3 increments of plain Newton to 20 deck length units); the best "
        f"imbalance reached {st.imbalance:.3g} (max_imbalance 1e-08) with increment or "
        f"constraint violation {st.error:.3g}")


def test_a_static_converged_after_the_search_counts_both_passes(decks):
    """Plain Newton cycles at the groove's contact onsets and gives way to the step-halving
    search; the message and the record count the iterations of both."""
    res = with_method(decks, "static_seed3.xml", "FIM_S").run()
    st = res.statics[0]
    found = re.fullmatch(r"FIM_S converged in (\d+) iterations \(with step halving, after "
                         r"(\d+) plain iterations\)", st.message)
    assert found, st.message
    total, plain = map(int, found.groups())
    assert total == st.iterations and plain < total


def test_compliance_is_the_inverse_stiffness(decks):
    """A small extra vertical load F moves the rest point by C F (C from the static result)."""
    base = load(decks, "static_neutral_floor.xml").run()
    C = base.compliance
    assert base.statics[0].coordinates == ["body2.dx", "body2.dy", "body2.dz"]
    extra = ('<Reference_Marker id="2" body_id="1" pos_x="0.3" pos_y="-0.2" pos_z="10"/>'
             '<Force_Scalar_TwoBody id="9" type="Force" i_marker_id="10" j_marker_id="2" '
             'val="1e-4"/><Post_Request')
    pushed = load(decks, "static_neutral_floor.xml", **{"<Post_Request": extra}).run()
    assert pushed.success, pushed.message
    dz = pushed.request(1)[0, 2] - base.request(1)[0, 2]
    # the force pushes away from marker 2 above: -0.01 N along z
    assert dz == pytest.approx(C[2, 2] * -1e-4, rel=1e-5)   # pushed down by 1e-4 N
    assert C[2, 2] > 0 and C[0, 2] == pytest.approx(0, abs=1e-15)
    # the neutral directions have the compliance of the stability term only: 1 / (sqrt(s) m)
    assert C[0, 0] == pytest.approx(1 / (math.sqrt(1e-10) * 2), rel=1e-12)


def test_quasi_static_fim_d_agrees_with_fim_s_and_costs_less(decks):
    fim_d = load(decks, "quasi_static_stack.xml").run()
    fim_s = load(decks, "quasi_static_stack.xml", **{'method="FIM_D"': 'method="FIM_S"'}).run()
    assert fim_d.success and fim_s.success
    np.testing.assert_array_equal(fim_d.t, fim_s.t)
    assert len(fim_d.t) == 101
    # every output an equilibrium: positions agree to max_error (1e-6)
    assert np.abs(fim_d.request(1)[:, :5] - fim_s.request(1)[:, :5]).max() < 1e-6
    # the floor carries the weight and the load 100 t
    np.testing.assert_allclose(fim_d.request(1)[:, 5], -(5 * 0.5 * 9.81 + 100 * fim_d.t),
                               rtol=1e-6)
    # FIM_D follows the path with IDA's predictor: fewer kernel evaluations than a Newton solve
    # per output (timings in benchmarks/statics.py)
    assert fim_d.stats["nres"] < 0.5 * fim_s.stats["nres"]
    assert fim_d.statics[0].success and fim_d.statics[-1].success and len(fim_d.statics) == 2


def test_static_and_python_statement(tmp_path):
    deck = tmp_path / "s.py"
    deck.write_text(
        "PART(1, GROUND=True)\nMARKER(10, PART=2, QP=[0, 0, 0.05])\nPOINT_MASS(2, MASS=2, CM=10)\n"
        "ACCGRAV(KGRAV=-9.81)\n"
        "PFORCE(1, FUNCTION='-DZ(10)', PENALTY=1e5, PENALTY1=100, UNILATERAL=True, "
        "SMOOTHING_FACTOR=1e-3)\n"
        "EQUILIBRIUM(METHOD='FIM_S', IMBALANCE=1e-9, ERROR=1e-12)\n"
        "REQUEST(1, F1='DZ(10)')\nSIMULATE(TYPE='STATIC')\n")
    res = pysolver.load(deck).run()
    assert res.success
    assert res.request(1)[0, 0] == pytest.approx(-rest_penetration(0.5e5, 2 * 9.81, 1e-3), abs=1e-12)


@pytest.mark.parametrize("attrs,attr,match", [
    ('method="NEWTON"', "method", "expected one of FIM_D, FIM_S, MKEAM"),
    ('max_imbalance="0"', "max_imbalance", "expected a value > 0"),
    ('stability="-1"', "stability", "expected a value >= 0"),
    ('max_num_iter="2.5"', "max_num_iter", "expected a positive integer"),
    ('compliance_delta="x"', "compliance_delta", "expected a real number"),
])
def test_bad_param_static(decks, attrs, attr, match):
    text = (decks / "static_seed3.xml").read_text().replace(
        '<Param_Static method="FIM_S" max_imbalance="1e-8" max_error="1e-10"/>',
        f'<Param_Static {attrs}/>')
    with pytest.raises(pysolver.DeckError, match=match) as info:
        pysolver.loads(text, file="s.xml")
    assert info.value.attribute == attr and info.value.element == "Param_Static"
    assert info.value.line == 17


def test_mkeam_quasi_static_is_rejected(decks):
    text = (decks / "quasi_static_stack.xml").read_text().replace('method="FIM_D"',
                                                                  'method="MKEAM"')
    with pytest.raises(pysolver.DeckError, match="MKEAM does not do quasi-static") as info:
        pysolver.loads(text)
    assert info.value.element == "Simulate" and info.value.attribute == "analysis_type"


#: A 2 kg arm (centre of mass 200 mm out, Iyy about it 1e4 kg mm^2) on a revolute about the
#: global y axis, its angle driven as 30 deg sin(2 pi t) (the rate not zero at
#: t = 0 for the sine; for 1 - cos the rate is zero and the acceleration is not), gravity
#: along -z.
ROCKER = """<MotionSolve><Model>
<Units force="NEWTON" mass="KILOGRAM" length="MILLIMETER" time="SECOND"/>
<Force_Gravity grav_z="-9810"/>
<Param_Transient integr_tol="1e-8"/>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="2" body_id="1" a00="1" a10="0" a20="0" a01="0" a11="0" a21="-1"
                  a02="0" a12="1" a22="0"/>
<Body_Rigid id="2" mass="2" cg_id="3" inertia_xx="1000" inertia_yy="10000" inertia_zz="10000"/>
<Reference_Marker id="3" body_id="2" pos_x="200"/>
<Reference_Marker id="4" body_id="2" a00="1" a10="0" a20="0" a01="0" a11="0" a21="-1"
                  a02="0" a12="1" a22="0"/>
<Constraint_Joint id="1" type="REVOLUTE" i_marker_id="4" j_marker_id="2"/>
<Motion_Joint id="1" joint_id="1" expr="{drive}" val_type="D" motion_type="R"/>
<Post_Request id="1" expr1="AZ(4,2)" expr2="WZ(4,2,2)" expr3="MOTION(1,0,8,2)"/>
</Model>{commands}
<Simulate analysis_type="TRANSIENT" end_time="0.5" num_step="50"/></MotionSolve>"""


@pytest.mark.parametrize("drive", ["30*DTOR*SIN(2*PI*TIME)", "30*DTOR*(1-COS(2*PI*TIME))"])
def test_a_transient_after_a_static_starts_with_the_motions_rates(drive):
    """Velocities zero and yp = 0 after the equilibrium broke the motion's rate (the sine:
    rate 2 pi 30 deg/s at t = 0) or its acceleration (1 - cos); the transient failed at
    t = 0 ("Error test failures occurred too many times"). Now its rows after the static one
    are those of the run without the static (the same transient from a consistent start)."""
    static = pysolver.loads(ROCKER.format(drive=drive, commands='<Simulate analysis_type='
                                          '"STATIC"/>')).run()
    plain = pysolver.loads(ROCKER.format(drive=drive, commands="")).run()
    assert static.success and plain.success, (static.message, plain.message)
    np.testing.assert_array_equal(static.t, plain.t)
    assert static.request(1)[0, 1] == 0.0           # the static's row: at rest
    got, want = static.request(1)[1:, :3], plain.request(1)[1:, :3]
    np.testing.assert_allclose(got[:, :2], want[:, :2], rtol=0, atol=1e-7)
    np.testing.assert_allclose(got[:, 2], want[:, 2], rtol=0, atol=1e-5 * np.abs(want[:, 2]).max())
    t = plain.t[1:]
    theta = math.radians(30) * (np.sin(2 * np.pi * t) if "SIN" in drive
                                else 1 - np.cos(2 * np.pi * t))
    np.testing.assert_allclose(want[:, 0], theta, rtol=0, atol=1e-9)


def test_a_transient_that_cannot_leave_the_equilibrium_is_a_failed_run(monkeypatch):
    """Where the motions' start cannot be made consistent after the static (here forced), the
    run ends with status -300 naming it, its static row kept."""
    from pysolver.build.consistent import AssemblyError
    from pysolver.build.kernel import Kernel

    def refuse(self, t, y, iters=4, initial=False, **kw):
        if not initial:
            raise AssemblyError("forced")
        return original(self, t, y, iters, initial, **kw)
    original = Kernel.consistent_yp
    monkeypatch.setattr(Kernel, "consistent_yp", refuse)
    res = pysolver.loads(ROCKER.format(drive="30*DTOR*SIN(2*PI*TIME)",
                                       commands='<Simulate analysis_type="STATIC"/>')).run()
    assert (res.success, res.status) == (False, -300)
    assert res.message == ("the transient after the static analysis at t = 0 cannot start: its "
                           "velocities and accelerations cannot be made consistent (forced)")
    assert len(res.t) == 1 and res.request(1)[0, 1] == 0.0
