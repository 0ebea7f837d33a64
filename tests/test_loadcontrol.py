"""The LoadControl task (seed 002) in a run: the load follows the target on a linear floor
(A_t exactly its stiffness) and on a Hertz-like contact (A_t the secant), the velocity changes
only at updates without spikes in the load, the Python statement equals the XML block, and bad
parameters are DeckErrors that say where."""
import numpy as np
import pytest

import pysolver

from helpers import DECKS


def _run(name):
    res = pysolver.load(DECKS / name).run()
    assert res.success, res.message
    return res, res.controller(1)


def test_linear_floor_A_is_the_stiffness_and_the_load_settles():
    """The floor is 100 N/mm: A_t = -100 N/mm (load positive, displacement negative) from the
    first loaded update; the step to 40 N at t = 2 s keeps auto_gains' promise (overshoot
    below 2 % of the step, within 2 % after 3 / (1 - sqrt(0.8)) = 28 updates); the body's
    velocity between updates is the one the controller set, and the recorded load is the floor
    force at every update (no spike)."""
    res, c = _run("loadcontrol_indenter.xml")
    loaded = ~np.isnan(c["A"])
    np.testing.assert_allclose(c["A"][loaded], -100.0, rtol=1e-6)
    t, load = c["time"], c["measured"]
    step = t >= 2.0
    assert load[step].max() <= 40.0 + 0.02 * 20.0
    outside = np.nonzero(np.abs(load[step] - 40.0) > 0.02 * 20.0)[0]
    assert outside[-1] + 1 <= 3 / (1 - np.sqrt(0.8))
    # the floor's push (-PFORCE: g = -DZ) in the output rows at the update times is the load
    rows = np.searchsorted(res.t, t)
    np.testing.assert_allclose(-res.request(1)[rows, 1], load, rtol=1e-9, atol=1e-9)
    # between updates the velocity is the controller's (vz = dz/dt of the rows)
    vz = res.y[1:, res.state_names.index("body2.vz")]
    np.testing.assert_allclose(vz[1:], c["velocity"][:len(vz) - 1], rtol=1e-9, atol=1e-12)


def test_hertz_contact_A_is_the_secant_and_auto_gains_settle():
    """On a floor pushing 100 (-z)^1.5 N the ratio A_t follows the secant -100 |z|^0.5 as the
    depth changes (within 1 % at the end), and with the gains chosen by the controller the load
    settles on the 40 N step (within 2 % of it by t = 2.5 s, and stays there)."""
    res, c = _run("loadcontrol_hertz.xml")
    z = c["displacement"][-1]
    assert abs(c["A"][-1] - (-100.0 * np.sqrt(-z))) <= 0.01 * 100.0 * np.sqrt(-z)
    t, load = c["time"], c["measured"]
    assert np.abs(load[t >= 2.5] - 40.0).max() <= 0.02 * 20.0


def test_python_statement_equals_the_xml_block():
    text = (DECKS / "loadcontrol_indenter.xml").read_text()
    py = '''from pysolver.msolve import *
UNITS(MASS="KILOGRAM", LENGTH="MILLIMETER", TIME="SECOND", FORCE="NEWTON")
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[0, 0, 0])
POINT_MASS(2, MASS=0.01, CM=10)
PFORCE(1, FUNCTION="-DZ(10)", PENALTY=100, UNILATERAL=True, SMOOTHING_FACTOR=1e-4)
REQUEST(1, F1="DZ(10)", F2="PFORCE(1)")
LOADCONTROL(1, VELOCITY=-0.1, MATERIAL=2, DIRECTION=3, MAXVELOCITY=10,
            LOAD_FUNCTION="IF(t-1: 20*t, 20, IF(t-2: 20, 40, 40))", KP="auto", KI="auto",
            SMOOTH=0.8, UPDATETIME=0.01)
INTEGRATOR(ERROR=1e-8)
SIMULATE(TYPE="TRANSIENT", END=3.0, DTOUT=0.01)
'''
    a = pysolver.loads(text).run().controller(1)
    b = pysolver.loads(py, fmt="py").run().controller(1)
    for name in a:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)


def _with(param, value):
    """The linear-floor deck with one parameter replaced (None: removed)."""
    text = (DECKS / "loadcontrol_indenter.xml").read_text()
    lines = text.splitlines(keepends=True)
    out = []
    for line in lines:
        if f'<Parameter name="{param}' in line:
            if value is not None:
                out.append(f'        <Parameter name="{param}">{value}</Parameter>\n')
            continue
        out.append(line)
    return "".join(out)


@pytest.mark.parametrize("text,attribute,match", [
    (_with("material", 7), "material", "material 7 is not a moving"),
    (_with("material", 1), "material", "material 1 is not a moving"),
    (_with("direction", 4), "direction", "expected one of 1, 2, 3"),
    (_with("smooth", 1.0), "smooth", "expected 0 < smooth < 1"),
    (_with("UpdateTime", 0), "UpdateTime", "expected a value > 0"),
    (_with("MaxVelocity", -1), "MaxVelocity", "expected a value > 0"),
    (_with("Kp", "fast"), "Kp", "expected a real number"),
    (_with("UpdateTime", None), "updatetime", "missing required"),
    ((DECKS / "loadcontrol_indenter.xml").read_text().replace(
        "Load_Function IF(t-1: 20*t, 20, IF(t-2: 20, 40, 40))", "Load_Function 20*t+"),
     "Load_Function", "bad Load_Function"),
    ((DECKS / "loadcontrol_indenter.xml").read_text().replace(
        "Load_Function IF(t-1: 20*t, 20, IF(t-2: 20, 40, 40))", "Load_Function 20*DZ(10)"),
     "Load_Function", "must depend on time only; it reads DZ"),
    ((DECKS / "loadcontrol_indenter.xml").read_text().replace(
        "<Post_Request", '<Motion_Marker id="1" i_marker_id="10" j_marker_id="1" '
        'direction="Z" val_type="V" expr="-1"/>\n    <Post_Request'),
     "material", "Motion_Marker 1 already drives body 2 along Z"),
    ((DECKS / "loadcontrol_indenter.xml").read_text().replace(
        'name="LoadControl"', 'name="LoadKontrol"'), None, "unknown element <LoadKontrol>"),
])
def test_bad_parameters(text, attribute, match):
    """Each names the <Parameter>'s own line (they all named the <Schedule>'s), or, for a
    missing one or the task's name, the <Schedule>'s."""
    with pytest.raises(pysolver.DeckError, match=match) as info:
        pysolver.loads(text)
    assert info.value.attribute == attribute
    lines = text.lower().splitlines()
    own = [k for k, ln in enumerate(lines, 1) if attribute and f'name="{attribute.lower()}' in ln]
    schedule = [k for k, ln in enumerate(lines, 1) if "<schedule" in ln]
    assert info.value.line == (own or schedule)[0]


def test_contact_load_is_the_floor_force():
    """load="contact" reads the penalties' force on the body; on the floor deck (no other
    force, the body at constant velocity between updates) it equals the drive's load
    (1e-12 relative) and the runs are the same."""
    text = (DECKS / "loadcontrol_indenter.xml").read_text().replace(
        '<Parameter name="UpdateTime">0.01</Parameter>',
        '<Parameter name="UpdateTime">0.01</Parameter>\n<Parameter name="load">contact</Parameter>')
    a = pysolver.load(DECKS / "loadcontrol_indenter.xml").run().controller(1)
    b = pysolver.loads(text).run().controller(1)
    np.testing.assert_allclose(b["measured"], a["measured"], rtol=1e-12, atol=1e-12)


def test_noisy_bed_with_a_median_filter():
    """decks/loadcontrol_bed.py (53 particles, every contact a penalty) with median_window 5,
    for 0.4 s: the contact load is fat-tailed (its update-to-update changes have kurtosis
    above 6; a Gaussian's is 3), the loop stays stable (never clamped), and at every update
    the indenter, at constant velocity, is in balance: contact load = weight - the drive's
    force (1e-8)."""
    text = (DECKS / "loadcontrol_bed.py").read_text().replace(
        "MEDIAN_WINDOW = 1", "MEDIAN_WINDOW = 5").replace("END=0.6", "END=0.4")
    res = pysolver.loads(text, fmt="py").run()
    assert res.success, res.message
    c = res.controller(1)
    assert not c["clamped"].any()
    d = np.diff(c["measured"])
    assert np.mean((d - d.mean()) ** 4) / np.var(d) ** 2 > 6
    rows = np.searchsorted(res.t, c["time"])
    weight = 5e-3 * 9.81
    np.testing.assert_allclose(c["measured"], weight - res.motion(-1)[rows], rtol=1e-8,
                               atol=1e-10)


def test_records_are_saved_and_plotted(tmp_path):
    """res.save writes the per-update records beside the requests (CSV) or inside (NPZ), equal
    to res.controller; res.plot draws a LoadControl panel."""
    res, c = _run("loadcontrol_indenter.xml")
    res.save(tmp_path / "r.csv")
    header, *rows = (tmp_path / "r_controller1.csv").read_text().splitlines()
    names = [cell.split(" [")[0] for cell in header.split(",")]
    table = np.array([row.split(",") for row in rows], dtype=float)
    for name in ("time", "target", "measured", "velocity"):
        np.testing.assert_array_equal(table[:, names.index(name)], c[name])
    res.save(tmp_path / "r.npz")
    with np.load(tmp_path / "r.npz") as z:
        np.testing.assert_array_equal(z["controller1_A"], c["A"])
    fig = res.plot()
    assert any(ax.get_title(loc="right") == "LoadControl 1" for ax in fig.axes)


def test_a_force_infinite_just_after_an_update_does_not_fail_its_restart():
    """The restart reads the rate rows' time derivative from residuals at t +- 1e-6: a force
    1e-9 / (TIME - 0.500001), infinite exactly at t + h of the update at 0.5 and finite at the
    update itself, leaves the restart consistent (as consistent() in Python, which reads the
    reactions' rows alone), and the run goes on through its 100 updates (the C restart failed
    it before stop 37, a review found). The force acts from a ground marker above the
    indenter (along z, as from marker 1 once the indenter has left it: at t = 0 the indenter
    sits on marker 1, where a force has no direction)."""
    text = (DECKS / "loadcontrol_indenter.xml").read_text().replace(
        'end_time="3.0"', 'end_time="1.0"').replace(
        "<Post_Request", '<Reference_Marker id="98" body_id="1" pos_z="1"/>'
        '<Force_Scalar_TwoBody id="99" type="Force" i_marker_id="10" '
        'j_marker_id="98" expr="1e-9/(TIME-0.500001)"/><Post_Request', 1)
    res = pysolver.loads(text).run(progress=False)
    assert res.success, res.message
    assert len(res.controller(1)["time"]) == 100


@pytest.mark.parametrize("name", ["joints/slider_crank.xml", "joints/spherical_pendulum.xml",
                                  "driven_indenter.xml", "joints/iftomm_a04_bricard.xml",
                                  # sparse: 325 states, one motion; 2,023 states, 485 equations
                                  "loadcontrol_bed.py", "joints/iftomm_a02_fourbar.xml"])
def test_the_c_restart_is_consistent_in_python(name):
    """The restart LoadControl's updates take in C (ps_restart_consistent, dense or on the
    kernel's sparse pattern) against consistent() in Python away from the start, from a state
    whose positions (1e-4) and velocities (1e-2) are off the constraints: the same y and yp to
    1e-9 of their size, the position rows then zero to 1e-10 and the force rows to 1e-8 (the
    rate rows hold g' + c lam, c the compliance); and ps_motion_reactions against
    consistent.reactions (least squares), 1e-9."""
    from pysolver.build.bindings import ffi, lib
    from pysolver.build.consistent import consistent, reactions
    from pysolver.build.restart import Restart
    model = pysolver.load(DECKS / name)
    k = model.compile().kernel
    res = model.run(progress=False)
    rng = np.random.default_rng(5)
    y0 = res.y[len(res.t) // 2].copy()
    lay = k.layout
    for qa, ua in zip(lay.qadr, lay.uadr):
        y0[qa:qa + 3] += 1e-4 * rng.standard_normal(3)
        y0[ua:ua + 3] += 1e-2 * rng.standard_normal(3)
    t = float(res.t[len(res.t) // 2])
    y_py = y0.copy()
    yp_py = consistent(k, t, y_py)
    y_c, yp_c = y0.copy(), np.zeros_like(y0)
    rs = Restart.of(k)
    assert rs.sparse == (k.ny >= 300)
    fb = ffi.from_buffer
    assert lib.ps_restart_consistent(k.m, k.d, rs.r, t, fb("double[]", y_c),
                                     fb("double[]", yp_c)) == lib.PS_OK
    for got, want in ((y_c, y_py), (yp_c, yp_py)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 * (1 + np.abs(want).max()))
    r = k.residual_array(t, y_c, yp_c)
    held = [m for m in lay.mu if m >= 0]
    force = np.setdiff1d(np.arange(k.ny), lay.algebraic)
    assert (np.abs(r[held]).max() if held else 0.0) <= 1e-10
    assert np.abs(r[force]).max() <= 1e-8 * (1 + np.abs(yp_c).max())
    lam = np.zeros(max(len(lay.lam), 1))
    assert lib.ps_motion_reactions(k.m, k.d, rs.r, t, fb("double[]", y_c), fb("double[]", yp_c),
                                   fb("double[]", lam)) == lib.PS_OK
    want = reactions(k, t, y_c, yp_c)
    np.testing.assert_allclose(lam[:len(want)], want, rtol=0,
                               atol=1e-9 * (1 + np.abs(want).max()))
