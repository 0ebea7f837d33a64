"""The benchmark scripts run (once, quickly) so that they cannot rot; their figures are in the
README and come from running them in full."""
import contextlib
import importlib.util
import io
import os
import shutil
import subprocess
import sys

import pytest

import pysolver

from helpers import ROOT

BENCH = ROOT / "benchmarks"


def _module(name):
    spec = importlib.util.spec_from_file_location(f"bench_{name}", BENCH / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _output(fn, *args):
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        fn(*args)
    return buf.getvalue()


def test_work_precision_report_runs(tmp_path):
    mod = _module("work_precision")
    out = _output(mod.oscillator, 1)
    assert "Damped oscillator" in out and "1e-10" in out
    _output(mod.write_report, tmp_path)
    rows = (tmp_path / "work_precision.csv").read_text().splitlines()
    assert rows[0] == "problem,solver,tolerance,max_error,final_error,l2_error,seconds"
    assert len(rows) == 1 + 4 * 5
    assert (tmp_path / "work_precision.png").read_bytes()[:4] == b"\x89PNG"


def test_sensor_accuracy_report_runs():
    out = _output(_module("sensor_accuracy").event_times)
    assert "contact onset" in out


def test_statics_report_runs():
    out = _output(_module("statics").main)
    assert "FIM_D" in out and "faster" in out


def test_pytest_benchmark_suite_runs_once():
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(pysolver.__file__)))
    p = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                        str(BENCH / "test_bench.py"), "--benchmark-disable", "-k",
                        "catenary or (chain and not 5000) or load or (stiff_pendulum and pysolver)"
                        " or (usersub and not untraceable)"],
                       capture_output=True, text=True, env=env,
                       cwd=str(BENCH))
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    assert " passed" in p.stdout


def test_usersub_report_runs():
    mod = _module("usersubs")
    out = _output(lambda: mod.call_cost(mod.forms(1, tols=(1e-4,))[0], 1))
    assert "untraceable" in out and "us per call" in out


def test_sparse_lu_report_runs(monkeypatch):
    mod = _module("sparse_lu")
    monkeypatch.setattr(sys, "argv", ["sparse_lu.py", "--quick"])
    out = _output(mod.main)
    assert "ratio SuperLU_MT / LU" in out and "| True |" in out


def test_actors_report_runs():
    """benchmarks/actors.py: every deck, its path (all batched: the sensor decks, zero_crossing
    included, the motion and the LoadControl decks, the sparse particle bed too) and its
    updates (300 on the LoadControl decks, 120 on the bed)."""
    out = _output(_module("actors").main, 1).splitlines()
    rows = {line.split()[0]: line.split() for line in out[1:]}
    assert len(rows) == 8
    for name in ("sensor_halt_acceleration.xml", "sensor_end_condition.xml",
                 "sensor_output_interval.xml", "contact_onset_zero_crossing.xml",
                 "driven_indenter.xml", "loadcontrol_indenter.xml", "loadcontrol_hertz.xml",
                 "loadcontrol_bed.py"):
        assert rows[name][1] == "batched", name
    assert rows["loadcontrol_indenter.xml"][3] == "300"
    assert rows["loadcontrol_bed.py"][3] == "120"


def _c_ida_copy(tmp_path):
    """benchmarks/c_ida in a folder of its own, beside csrc (its programs include from it)."""
    shutil.copytree(BENCH / "c_ida", tmp_path / "benchmarks" / "c_ida",
                    ignore=shutil.ignore_patterns("seed3_ida", "pendulum_ida"))
    (tmp_path / "csrc").symlink_to(ROOT / "csrc")
    return tmp_path / "benchmarks" / "c_ida"


def test_the_c_programs_build_with_the_benchmarks_interpreter(tmp_path, monkeypatch):
    """build.sh finds scikit-sundae's SUNDIALS through the interpreter running the benchmark,
    even when the python3 on PATH has no scikit-sundae (trial 44, defect 9)."""
    if shutil.which("gcc") is None:
        pytest.skip("no gcc to build the plain C programs")
    folder = _c_ida_copy(tmp_path)
    bare = tmp_path / "bin"
    bare.mkdir()
    (bare / "python3").write_text("#!/bin/sh\necho 'No module named sksundae' >&2\nexit 1\n")
    (bare / "python3").chmod(0o755)
    monkeypatch.setenv("PATH", f"{bare}{os.pathsep}{os.environ['PATH']}")
    _module("work_precision").build_c_programs(folder)
    assert (folder / "seed3_ida").exists() and (folder / "pendulum_ida").exists()


def test_a_failed_build_of_the_c_programs_shows_its_error(tmp_path):
    """A build that fails is a RuntimeError carrying the build's own error output, not a bare
    CalledProcessError."""
    folder = _c_ida_copy(tmp_path)
    (folder / "build.sh").write_text("echo 'ModuleNotFoundError: No module named sksundae' >&2"
                                     "\nexit 3\n")
    with pytest.raises(RuntimeError) as err:
        _module("work_precision").build_c_programs(folder)
    assert str(err.value) == (
        f"building the plain C programs ({folder / 'build.sh'}, with PYTHON={sys.executable}) "
        "failed with exit status 3:\nModuleNotFoundError: No module named sksundae")
