"""The LoadControl law (seed 002, pysolver/solve/loadlaw.py): every logged quantity equals a
direct NumPy transcription of the seed's formulas; on an exact linear spring the ratio A is the
stiffness from the first loaded update on and the load settles on the target; the median
filter, the MaxVelocity clamp and bad parameters behave as documented."""
import math

import numpy as np
import pytest

from pysolver.solve.loadlaw import FIELDS, LawParams, LoadLaw


def seed_transcription(x, L, target, a, kp, ki, vmax, v0):
    """The seed's formulas over whole arrays, one update per entry (no median filter), with
    the start decided as in loadlaw.py: A unknown (velocity v0) until L != 0 and x != 0."""
    n = len(x)
    A, e, Ie, e2, De, V = (np.full(n, np.nan) for _ in range(6))
    A_prev, e_prev, Ie_prev, e2_prev, v = None, 0.0, 0.0, 0.0, v0
    for k in range(n):
        if A_prev is None:
            A_k = L[k] / x[k] if L[k] != 0 and x[k] != 0 else None
        else:
            lam = 2 * (1 - a) / (L[k] ** 2 + (A_prev * x[k]) ** 2)
            gam = a / A_prev ** 2
            A_k = (lam * L[k] * x[k] + gam * A_prev) / (lam * x[k] ** 2 + gam)
        if A_k is None:
            e[k], Ie[k], De[k], V[k] = 0.0, 0.0, 0.0, v
            continue
        e[k] = (1 - a) * (target[k] - L[k]) / A_k + a * e_prev
        Ie_k = (target[k] - L[k]) / A_k + Ie_prev
        e2_k = (1 - a) * e[k] + a * e2_prev
        De[k] = (1 - a) / a * (e[k] - e2_k)
        v = kp * e[k] + ki * Ie_k + 0.25 * ki * De[k]
        if abs(v) > vmax:
            v, Ie_k = math.copysign(vmax, v), Ie_prev
        A[k], Ie[k], V[k] = A_k, Ie_k, v
        A_prev, e_prev, Ie_prev, e2_prev = A_k, e[k], Ie_k, e2_k
    return dict(A=A, e=e, Ie=Ie, De=De, velocity=V)


def test_replay_matches_the_seed_formulas():
    """A recorded indentation (load grows with depth, noisy, signs negative as for a body
    pressing down) replayed through the controller: every logged quantity within 1e-12."""
    rng = np.random.default_rng(3)
    n = 400
    x = -np.concatenate([np.zeros(5), np.cumsum(rng.uniform(0, 2e-3, n - 5))])
    L = 5e3 * (-x) ** 1.2 * (1 + 0.05 * rng.standard_normal(n))
    L[:5] = 0.0
    target = 40.0 * np.linspace(0, 1, n)
    a, kp, ki, vmax, v0 = 0.9, 20.0, 2.0, 0.5, -0.1
    law = LoadLaw(LawParams(velocity=v0, max_velocity=vmax, kp=kp, ki=ki, smooth=a))
    for k in range(n):
        law.update(k * 1e-2, x[k], L[k], target[k])
    log = dict(zip(FIELDS, np.array(law.log, dtype=float).T))
    ref = seed_transcription(x, L, target, a, kp, ki, vmax, v0)
    for name, want in ref.items():
        got = log[name]
        assert np.array_equal(np.isnan(got), np.isnan(want)), name
        ok = ~np.isnan(want)
        np.testing.assert_allclose(got[ok], want[ok], rtol=1e-12, atol=1e-12 * np.abs(want[ok]).max(),
                                   err_msg=name)
    assert log["clamped"].any() and not log["clamped"].all()   # the clamp was exercised
    np.testing.assert_array_equal(log["filtered"], L)           # no median filter


def test_on_a_linear_spring_A_is_the_stiffness_and_the_load_settles():
    """Plant: the body moves by V dt per update, the load is k x (k < 0: pressing down gives a
    positive load). A = L / x exactly from the first loaded update; with the critically damped
    proportional gain of the smoothed loop, Kp dt = (1 - sqrt(a)) / (1 + sqrt(a)), a step in the
    target settles without overshoot."""
    k, dt, a, target = -2.0e4, 1e-3, 0.5, 10.0
    kp = (1 - math.sqrt(a)) / (1 + math.sqrt(a)) / dt
    law = LoadLaw(LawParams(velocity=-1e-3, kp=kp, ki=0.0, smooth=a))
    x = 0.0
    loads = []
    for i in range(200):
        load = k * x
        v = law.update(i * dt, x, load, target)
        loads.append(load)
        x += v * dt
    A = np.array([row[FIELDS.index("A")] for row in law.log])
    known = ~np.isnan(A)
    assert known.sum() >= 198
    np.testing.assert_allclose(A[known], k, rtol=1e-12)
    assert abs(loads[-1] - target) < 1e-6 * target
    assert max(loads) <= target * (1 + 1e-9)                  # no overshoot


def test_median_window_removes_an_isolated_spike():
    law = LoadLaw(LawParams(velocity=-1.0, median_window=5))
    loads = [1.0, 1.1, 50.0, 1.2, 1.3, 1.25]
    for i, load in enumerate(loads):
        law.update(i, -(i + 1) * 1e-3, load, 2.0)
    filtered = [row[FIELDS.index("filtered")] for row in law.log]
    assert filtered == [1.0, 1.05, 1.1, 1.15, 1.2, 1.25]
    assert max(filtered) < 2.0


def test_clamp_keeps_the_integral():
    law = LoadLaw(LawParams(velocity=-1.0, kp=1e6, ki=1.0, max_velocity=2.0, smooth=0.5))
    law.update(0.0, -1e-3, 1.0, 1.0)          # A = -1000, no error yet
    v = law.update(1.0, -1e-3, 1.0, 1e6)      # a huge error: clamped, Ie not accrued
    assert v == 2.0 * math.copysign(1.0, v) and law.log[-1][-1] is True
    assert law.ie == 0.0


@pytest.mark.parametrize("kw,match", [
    (dict(smooth=1.0), "smooth"), (dict(smooth=0.0), "smooth"),
    (dict(max_velocity=0.0), "MaxVelocity"), (dict(median_window=0), "median_window"),
    (dict(median_window=2.5), "median_window"), (dict(kp=math.nan), "kp")])
def test_bad_parameters(kw, match):
    with pytest.raises(ValueError, match=match):
        LoadLaw(LawParams(velocity=1.0, **kw))


@pytest.mark.parametrize("a", [0.5, 0.8, 0.95])
def test_auto_gains_step_response(a):
    """auto_gains' promise on the closed loop (exact spring, from rest): a step in the target
    overshoots by less than 2 % and settles to 2 % within 3 / (1 - sqrt(a)) updates."""
    from pysolver.solve.loadlaw import auto_gains
    dt, k, target = 1e-2, -50.0, 10.0
    kp, ki = auto_gains(a, dt)
    law = LoadLaw(LawParams(velocity=-1e-4, kp=kp, ki=ki, smooth=a))
    x, loads = 0.0, []
    for i in range(int(30 / (1 - math.sqrt(a)))):
        load = k * x
        loads.append(load)
        x += law.update(i * dt, x, load, target if i >= 1 else 0.0) * dt
    loads = np.array(loads)
    assert loads.max() < target * 1.02
    outside = np.nonzero(np.abs(loads - target) > 0.02 * target)[0]
    assert outside[-1] + 1 <= 3 / (1 - math.sqrt(a))


def test_a_ratio_past_the_float_range_keeps_the_last_one():
    """Found by the fuzzer: A_{t-1} = 1e200 made (A x)^2 raise OverflowError. The update is now
    inf there and is rejected like any non-finite ratio: A stays."""
    law = LoadLaw(LawParams(velocity=-1.0, smooth=0.5))
    law.update(0.0, -1e-200, 1.0, 1.0)           # first A = L / x = -1e200
    assert law.A == -1e200
    law.update(1.0, -2e-200, 1.0, 1.0)
    assert law.A == -1e200


def test_a_ratio_update_that_underflows_keeps_the_last_one():
    """Found by the fuzzer: L^2 + (A x)^2 underflowed to 0 (ZeroDivisionError)."""
    law = LoadLaw(LawParams(velocity=-1.0, smooth=0.5))
    law.update(0.0, -1e-170, 1e-170, 1.0)         # first A = -1
    law.update(1.0, -2e-170, 1e-170, 1.0)         # L^2 and (A x)^2 are below 1e-323
    assert law.A == -1.0 and math.isfinite(law.velocity)


def _c_law(params):
    """The C law (ps_law_update, csrc/control.c) with `params`; returns (law, step) where
    step(t, x, load, target) runs one update and returns its log row."""
    from pysolver.build.bindings import ffi, lib
    w = ffi.new("psLaw *")
    w.velocity0, w.max_velocity, w.kp, w.ki = (params.velocity, params.max_velocity, params.kp,
                                               params.ki)
    w.smooth, w.window = params.smooth, params.median_window
    buffers = np.zeros(params.median_window), np.zeros(params.median_window)
    w.loads, w.sorted = (ffi.cast("double *", ffi.from_buffer(b)) for b in buffers)
    lib.ps_law_reset(w)
    row = np.zeros(len(FIELDS))

    def step(t, x, load, target):
        lib.ps_law_update(w, t, x, load, target, ffi.cast("double *", ffi.from_buffer(row)))
        return row.copy()
    step.keep = buffers
    return w, step


@pytest.mark.parametrize("window", [1, 4, 5])
def test_the_c_law_is_the_python_law(window):
    """The law the runs use is C's (both paths of a run call it); this module's Python is its
    reference: on the noisy indentation with contact lost and regained, sign flips refused and
    the clamp reached, every logged field agrees to 1e-14 (relative to the field's size) in
    every update."""
    rng = np.random.default_rng(11)
    n = 300
    x = -np.concatenate([np.zeros(5), np.cumsum(rng.uniform(0, 2e-3, n - 5))])
    L = 5e3 * (-x) ** 1.2 * (1 + 0.2 * rng.standard_normal(n))
    L[:5] = 0.0
    L[100:104] = 0.0                       # contact lost for a while
    L[150] = -L[150]                       # a load that would flip A's sign
    target = 60.0 * np.linspace(0, 1, n)
    params = LawParams(velocity=-0.1, max_velocity=0.05, kp=20.0, ki=2.0, smooth=0.9,
                       median_window=window)
    law, (w, step) = LoadLaw(params), _c_law(params)
    rows = []
    for k in range(n):
        law.update(k * 1e-2, x[k], L[k], target[k])
        rows.append(step(k * 1e-2, x[k], L[k], target[k]))
    want, got = np.array(law.log, dtype=float), np.array(rows)
    assert np.array_equal(np.isnan(got), np.isnan(want))
    assert 0 < want[:, FIELDS.index("clamped")].sum() < n      # the clamp acted, not always
    scale = np.nanmax(np.abs(want), axis=0) + 1e-300
    assert np.all(np.nan_to_num(np.abs(got - want)) <= 1e-14 * scale)
    assert w.velocity == got[-1, FIELDS.index("velocity")]
