"""The public API: load, run, Result and its writers, pickling, failures, the CLI."""
import json
import os
import pickle
import subprocess
import sys
import tempfile

import numpy as np
import pytest

import pysolver


@pytest.fixture
def bead(decks):
    return pysolver.load(decks / "catenary_bead.xml")


def test_result_shapes_and_null_channels(bead):
    res = bead.run()
    assert res.success and res.status == 0
    n = len(res.t)
    assert res.t[0] == 0.0 and res.t[-1] == 3.0 and n == 301
    np.testing.assert_allclose(np.diff(res.t), 0.01, rtol=1e-9)
    R = res.request(1)
    assert R.shape == (n, 8)
    assert np.all(np.isnan(R[:, 6:])) and not np.any(np.isnan(R[:, :6]))
    assert res.y.shape == (n, 6) and res.state_names[0] == "body2.x"
    with pytest.raises(KeyError, match=r"no Post_Request 5 \(requests: 1\)"):
        res.request(5)


def test_run_is_repeatable(bead):
    a, b = bead.run(), bead.run()
    np.testing.assert_array_equal(a.request(1), b.request(1))
    assert a.stats == b.stats


def test_pickle_round_trip(bead):
    clone = pickle.loads(pickle.dumps(bead))
    np.testing.assert_array_equal(clone.run().request(1), bead.run().request(1))


def test_save_csv_npz_and_dataframe(bead, tmp_path):
    res = bead.run()
    res.save(tmp_path / "r.csv")
    header, *rows = (tmp_path / "r.csv").read_text().splitlines()
    assert header == "time [s],x [m],y [m],vx [m/s],vy [m/s],g,penalty_force [N]"
    data = np.array([row.split(",") for row in rows], dtype=float)
    np.testing.assert_array_equal(data[:, 0], res.t)
    np.testing.assert_array_equal(data[:, 5], res.request(1)[:, 4])
    res.save(tmp_path / "r.npz")
    z = np.load(tmp_path / "r.npz")
    np.testing.assert_array_equal(z["request_1"], res.request(1))
    df = res.to_dataframe()
    assert list(df.columns[:2]) == ["x [m]", "y [m]"] and len(df) == len(res.t)
    with pytest.raises(ValueError, match="use .csv or .npz"):
        res.save(tmp_path / "r.txt")


def test_plot_writes_png(bead, tmp_path):
    bead.run().plot(tmp_path / "p.png")
    assert (tmp_path / "p.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_failed_integration_returns_result(bead):
    res = bead.run(max_num_steps=20)
    assert not res.success and res.status == -100
    assert "max_num_steps" in res.message
    assert 1 <= len(res.t) < 301          # rows up to the failure are kept
    with pytest.raises(TypeError, match="unknown run option"):
        bead.run(tolerance=1e-3)


def test_h_max_bounds_the_step(bead):
    free = bead.run()
    capped = bead.run(h_max=1e-3)
    assert capped.stats["steps"] >= 3000 > free.stats["steps"]


def test_several_simulate_commands_continue(decks):
    text = (decks / "catenary_bead.xml").read_text().replace(
        '<Simulate analysis_type="Transient" end_time="3.0" print_interval="0.01"/>',
        '<Simulate analysis_type="Transient" end_time="1.0" print_interval="0.01"/>\n'
        '<Simulate analysis_type="Transient" end_time="3.0" print_interval="0.02"/>')
    two = pysolver.loads(text).run()
    one = pysolver.load(decks / "catenary_bead.xml").run(integr_tol=1e-6)
    assert len(two.t) == 101 + 100 and two.t[-1] == 3.0
    np.testing.assert_allclose(np.diff(two.t[101:]), 0.02, rtol=1e-9)
    # same physics either way, to the integration tolerance
    np.testing.assert_allclose(two.request(1)[100, :2], one.request(1)[100, :2], atol=1e-5)


def _cli(*args):
    # the subprocess imports the same pysolver as these tests (not a checkout in its cwd)
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(pysolver.__file__)))
    return subprocess.run([sys.executable, "-m", "pysolver", *args], capture_output=True,
                          text=True, env=env, cwd=tempfile.gettempdir())


def test_cli_run_and_check(decks, tmp_path):
    out = tmp_path / "out"
    p = _cli("run", str(decks / "particle_between_lines.py"), "-o", str(out), "-q")
    assert p.returncode == 0, p.stderr
    assert (out / "requests.csv").exists() and (out / "requests.png").exists()
    stats = json.loads((out / "stats.json").read_text())
    assert stats["success"] and stats["stats"]["steps"] > 0
    p = _cli("check", str(decks / "torque_free_spin.xml"))
    assert p.returncode == 0 and "1 rigid" in p.stdout and "deck is valid" in p.stdout


def test_cli_reports_deck_errors(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text("<MotionSolve><Model><Body_Point id='2'/></Model></MotionSolve>")
    p = _cli("check", str(bad))
    assert p.returncode == 2
    assert "bad.xml:1, Body_Point id=2, attribute 'cg_id'" in p.stderr
