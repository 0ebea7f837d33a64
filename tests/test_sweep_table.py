"""A sweep's table has the columns of its design: the same names in the same order whichever
case comes first or fails, every output even when no case ran, NaN (an empty CSV cell) where a
case has no value; in sw.table, sw.rows, sw.to_dataframe(), the command line's table.csv and a
sweep resumed from its folder. pysolver.sample refuses a number of cases that is not one."""
import csv
import math

import numpy as np
import pytest

import pysolver

from helpers import DECKS

DECK = DECKS / "particle_between_lines.xml"
MASS, PEN = "Body_Point/2/mass", "Force_Penalty/1/penalty"
OUT = {"x": "final:request/1/1", "z_min": "min:request/1/2"}
COLUMNS = ["case", MASS, "status", "message", "wall", "steps", "x", "z_min", "resumed"]
BAD = "Body_Point id=2, attribute 'mass': sweep parameter 'Body_Point/2/mass': got -1; " \
      "expected a value > 0"


def _sweep(cases, **kw):
    return pysolver.sweep(DECK, cases, processes=0, outputs=OUT, **kw)


def test_the_columns_do_not_depend_on_which_case_comes_first():
    bad_first = _sweep([{MASS: -1.0}, {MASS: 1.0}])
    good_first = _sweep([{MASS: 1.0}, {MASS: -1.0}])
    for sw in (bad_first, good_first):
        assert sw.columns == COLUMNS
        assert list(sw.table) == COLUMNS
        assert [list(r) for r in sw.rows] == [COLUMNS, COLUMNS]
    ok = pysolver.load(DECK).run(progress=False).request(1)
    assert bad_first.table["status"].tolist() == ["error", "ok"]
    assert bad_first.rows[0]["message"] == BAD
    assert bad_first.table["x"][1] == good_first.table["x"][0] == ok[-1, 0]
    assert bad_first.table["z_min"][1] == np.nanmin(ok[:, 1])
    assert np.isnan(bad_first.table["x"][0]) and np.isnan(good_first.table["x"][1])
    assert np.isnan(bad_first.table["steps"][0])
    assert (bad_first.rows[0]["x"], bad_first.rows[0]["steps"]) == (None, None)


def test_a_sweep_of_errors_only_keeps_its_output_columns():
    sw = _sweep([{MASS: -1.0}, {MASS: -2.0}])
    assert list(sw.table) == COLUMNS
    assert sw.table["x"].dtype == float and np.isnan(sw.table["x"]).all()
    assert np.isnan(sw.table["z_min"]).all() and np.isnan(sw.table["steps"]).all()
    assert str(sw.table).splitlines()[-1] == "[2 rows x 9 columns]"
    pd = pytest.importorskip("pandas")
    df = sw.to_dataframe()
    assert isinstance(df, pd.DataFrame) and df.index.name == "case"
    assert list(df.columns) == COLUMNS[1:]
    assert df["x"].dtype == float and df["x"].isna().all() and df["steps"].isna().all()


def test_the_outputs_keep_the_order_given():
    sw = pysolver.sweep(DECK, [{MASS: -1.0}, {PEN: 2e4}], processes=0,
                        outputs={"z_min": OUT["z_min"], "x": OUT["x"], "steps": "steps"})
    assert sw.columns == ["case", MASS, PEN, "status", "message", "wall", "steps", "z_min", "x",
                          "resumed"]
    assert sw.rows[1][MASS] is None and np.isnan(sw.table[MASS][1])
    assert sw.rows[0][PEN] is None and sw.table[PEN][0] != sw.table[PEN][0]
    assert sw.rows[1]["steps"] == sw.result(1).stats["steps"]


@pytest.mark.parametrize("name", ["status", "case", "message", "wall", "resumed", MASS])
def test_an_output_named_as_another_column_is_refused(name):
    with pytest.raises(ValueError) as err:
        pysolver.sweep(DECK, [{MASS: 1.0}], processes=0, outputs={name: OUT["x"]})
    assert str(err.value) == f"output {name!r}: the table has a column {name!r} already " \
                             "(case, the paths of the cases, status, message, wall, steps, " \
                             "resumed); choose another name"


def test_an_output_steps_is_the_steps_column_only_as_the_spec_steps():
    with pytest.raises(ValueError, match="^output 'steps': the table has a column 'steps'"):
        pysolver.sweep(DECK, [{}], processes=0, outputs={"steps": OUT["x"]})


def test_a_resumed_sweep_keeps_the_columns(tmp_path):
    first = _sweep([{MASS: -1.0}, {MASS: 1.0}], directory=tmp_path)
    again = _sweep([{MASS: -1.0}, {MASS: 1.0}], directory=tmp_path, keep="all")
    assert [r["resumed"] for r in again.rows] == [True, True]
    assert list(again.table) == COLUMNS and [list(r) for r in again.rows] == [COLUMNS] * 2
    assert again.table["x"][1] == first.table["x"][1] and np.isnan(again.table["x"][0])
    # only the bad case stored: the good one runs now, after it in the rows
    errors_only = _sweep([{MASS: -1.0}], directory=tmp_path / "e")
    mixed = _sweep([{MASS: -1.0}, {MASS: 1.0}], directory=tmp_path / "e", keep="all")
    assert [r["resumed"] for r in mixed.rows] == [True, False]
    assert list(errors_only.table) == list(mixed.table) == COLUMNS


def test_the_command_lines_table_has_the_same_columns(tmp_path, capsys):
    from pysolver.cli import main

    def header_and_rows(folder, values):
        args = ["sweep", str(DECK), "--set", f"{MASS}={values}", "--column",
                "x=final:request/1/1", "--column", "z_min=min:request/1/2", "-j", "0", "-o",
                str(folder), "-q"]
        code = main(args)
        with open(folder / "table.csv", newline="", encoding="utf-8") as fh:
            rows = list(csv.reader(fh))
        return code, rows[0], rows[1:]

    for values in ("-1,1", "1,-1", "-1,-2"):
        code, header, rows = header_and_rows(tmp_path / values, values)
        assert code == 1 and header == COLUMNS
        bad = [r for r in rows if r[2] == "error"]
        assert all(r[5] == r[6] == r[7] == "" for r in bad)
    code, header, rows = header_and_rows(tmp_path / "-1,1", "-1,1")      # resumed
    assert header == COLUMNS and [r[-1] for r in rows] == ["False", "True"]
    assert float(rows[1][6]) == pysolver.load(DECK).run(progress=False).request(1)[-1, 0]
    assert main(["sweep", str(DECK), "--set", f"{MASS}=1", "--column", "status=steps", "-j",
                 "0", "-o", str(tmp_path / "clash"), "-q"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1] == "pysolver: error: --column 'status': the table has a column 'status' " \
                      "already (case, the paths of the cases, status, message, wall, steps, " \
                      "resumed); choose another name"


@pytest.mark.parametrize("method", ["sobol", "lhs"])
@pytest.mark.parametrize("n", [0, -3, 2.5, 4.0, True, "8", None])
def test_sample_refuses_a_number_of_cases_that_is_not_one(method, n):
    with pytest.raises(ValueError) as err:
        pysolver.sample({PEN: (5e3, 2e4)}, n, method=method, seed=1)
    assert str(err.value) == f"n must be an integer of at least 1 (the number of cases), " \
                             f"got {n!r}"


def test_sample_takes_any_whole_number_of_cases():
    for method in ("sobol", "lhs"):
        assert len(pysolver.sample({PEN: (5e3, 2e4)}, 1, method=method, seed=1)) == 1
        got = pysolver.sample({PEN: (5e3, 2e4)}, np.int64(4), method=method, seed=1)
        assert len(got) == 4 and all(5e3 <= c[PEN] <= 2e4 and not math.isnan(c[PEN])
                                     for c in got)


def test_a_path_given_twice_is_refused_before_any_case_runs(tmp_path, capsys):
    """Paths are case-insensitive: two spellings in one case, one path spelled two ways across
    cases, a repeated --set or a repeated CSV column are each one clear error (trial 44,
    defect 4), never a case run with one of the values and shown with the other."""
    from pysolver.cli import main
    twice = [{PEN: 5e3, "force_penalty/1/PENALTY": 2e4}]
    with pytest.raises(ValueError) as err:
        _sweep(twice)
    assert str(err.value) == ("case 0 gives one path twice, as 'Force_Penalty/1/penalty' and "
                              "'force_penalty/1/PENALTY' (paths are case-insensitive)")
    with pytest.raises(ValueError) as err:
        _sweep([{PEN: 5e3}, {"force_penalty/1/PENALTY": 2e4}])
    assert str(err.value) == ("the cases spell one path two ways, 'Force_Penalty/1/penalty' "
                              "and 'force_penalty/1/PENALTY' (case 1); paths are "
                              "case-insensitive: use one spelling")
    with pytest.raises(pysolver.DeckError) as err:
        pysolver.load(DECK).run(params=twice[0])
    assert err.value.reason == ("sweep parameter 'Force_Penalty/1/penalty': given twice in one "
                                "case, as 'Force_Penalty/1/penalty' and "
                                "'force_penalty/1/PENALTY' (paths are case-insensitive)")
    base = ["sweep", str(DECK), "-j", "0", "-o", str(tmp_path / "out"), "-q"]
    assert main(base + ["--set", f"{PEN}=5000", "--set", f"{PEN}=20000"]) == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        f"pysolver: error: --set: one path given twice, '{PEN}=5000' and '{PEN}=20000' (paths "
        "are case-insensitive); give its values once, --set PATH=V1,V2,...")
    table = tmp_path / "cases.csv"
    table.write_text(f"{PEN},{PEN.upper()}\n5000,20000\n")
    assert main(base + ["--cases", str(table)]) == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        f"pysolver: error: --cases {table}: columns 1 ('{PEN}') and 2 ('{PEN.upper()}') name one "
        "path (paths are case-insensitive); give each path one column")
    assert not (tmp_path / "out").exists()
