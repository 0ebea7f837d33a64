"""Output files and long runs (issue 13): the C CSV writer writes exactly what the csv module
wrote (each number as repr writes it, so it reads back to the same double), and a run with a
million output rows stays within a bounded multiple of its data's size."""
import csv
import os
import pathlib
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import pysolver
from pysolver.results import _write_csv

from helpers import DECKS

SPECIAL = [0.0, -0.0, 1.0, -1.0, 0.1, 1 / 3, 1e15, 1e16, 1e-4, 1e-5, 123456789012345680.0,
           5e-324, 1.7976931348623157e308, 2.0 ** 53, 9007199254740993.0, 1e22, 1e23, 0.5,
           12345.678, float("nan"), float("inf"), -float("inf")]


def _python_csv(path, names, data):
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for row in data:
            w.writerow([repr(float(v)) for v in row])


def test_the_c_writer_writes_what_the_csv_module_wrote(tmp_path):
    rng = np.random.default_rng(7)
    mags = 10.0 ** rng.integers(-320, 308, 30_000)
    bits = rng.integers(0, 2 ** 63, 30_000, dtype=np.int64).view(np.float64)  # any double
    values = np.concatenate([rng.standard_normal(30_000) * mags, bits, SPECIAL])
    values = np.resize(values, (len(values) + 4) // 5 * 5).reshape(-1, 5)
    names = ["time", "a,b", 'quote"d', "x", "y"]          # header cells the csv module quotes
    _write_csv(tmp_path / "c.csv", names, values)
    _python_csv(tmp_path / "py.csv", names, values)
    assert (tmp_path / "c.csv").read_bytes() == (tmp_path / "py.csv").read_bytes()
    # and every number reads back to the same double
    with open(tmp_path / "c.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    back = np.array(rows[1:], dtype=float)
    same = (back == values) | (np.isnan(back) & np.isnan(values))
    assert same.all() and (np.signbit(back) == np.signbit(values)).all()


def test_a_csv_that_cannot_be_written_is_an_os_error(tmp_path):
    with pytest.raises(FileNotFoundError, match="No such file"):
        _write_csv(tmp_path / "missing" / "out.csv", ["time"], np.zeros((3, 1)))


def test_empty_and_wide_tables(tmp_path):
    _write_csv(tmp_path / "empty.csv", ["time", "x"], np.zeros((0, 2)))
    assert (tmp_path / "empty.csv").read_text() == "time,x\n"
    wide = np.arange(60_000.0).reshape(1, -1)            # one row longer than the buffer
    _write_csv(tmp_path / "wide.csv", [f"c{i}" for i in range(60_000)], wide)
    with open(tmp_path / "wide.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    assert np.array_equal(np.array(rows[1], dtype=float), wide[0])


RSS_SCRIPT = textwrap.dedent("""
    import json, resource, sys
    import pysolver
    deck = sys.argv[1]
    pysolver.load(deck).run(progress=False).save(sys.argv[2] + "/small.csv")
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    text = open(deck).read().replace('end_time="3.0"', 'end_time="5000"')
    res = pysolver.loads(text).run(progress=False)
    res.save(sys.argv[2] + "/big.csv")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    raw = res.t.nbytes + res.y.nbytes + res.yp.nbytes + 8 * len(res.t) * len(res.columns()[0])
    print(json.dumps({"base": base, "peak": peak, "raw": raw, "rows": len(res.t),
                      "success": res.success}))
""")


def test_a_million_output_rows_stay_within_three_times_their_size(tmp_path):
    """Seed 3 for 5000 s every 5 ms: 1,000,001 rows (6 states, their rates, 4 channels). Before
    the rows were joined block by block and times kept as arrays the run took 3.5x its data."""
    import json
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(pysolver.__file__).parents[1]))
    out = subprocess.run([sys.executable, "-c", RSS_SCRIPT,
                          str(DECKS / "particle_between_lines.xml"), str(tmp_path)],
                         capture_output=True, text=True, env=env, timeout=300, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    r = json.loads(out.stdout)
    assert r["success"] and r["rows"] == 1_000_001
    assert r["peak"] - r["base"] <= 3 * r["raw"], r
    with open(tmp_path / "big.csv", "rb") as fh:
        assert sum(1 for _ in fh) == 1_000_002


def test_names_with_commas_and_quotes_read_back_as_the_docs_say(tmp_path):
    """Trial 44, defect 8: docs/usage.md's NumPy recipe (names=True) cannot read a quoted
    header; the readers it names instead give the names and numbers back exactly."""
    text = (DECKS / "particle_between_lines.xml").read_text().replace(
        'end_time="3.0"', 'end_time="0.01"').replace('name1="x"', 'name1="a,b"').replace(
        'name2="z"', 'name2="say &quot;hi&quot;"')
    res = pysolver.loads(text).run(progress=False)
    path = tmp_path / "r.csv"
    res.save(path)
    assert path.read_text().splitlines()[0] == \
        'time [s],"a,b [mm]","say ""hi"" [mm]",force_L1 [N],force_L2 [N]'
    with open(path, newline="") as fh:
        header = next(csv.reader(fh))
    assert header == res.columns(units=True)[0] == [
        "time [s]", "a,b [mm]", 'say "hi" [mm]', "force_L1 [N]", "force_L2 [N]"]
    np.testing.assert_array_equal(np.loadtxt(path, delimiter=",", skiprows=1),
                                  res.columns()[1])
    pd = pytest.importorskip("pandas", reason="pandas is not installed")
    df = pd.read_csv(path)
    assert list(df.columns) == header
    np.testing.assert_array_equal(df.to_numpy(), res.columns()[1])
