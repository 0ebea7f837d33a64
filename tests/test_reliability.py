"""Issue 13's defects, each with the input that showed it: every bad deck is a DeckError (file,
line, element, attribute, what was expected), never a traceback into internals; constants that
are infinite or NaN are refused at load; output grids that cannot fit are refused before any
memory is taken."""
import re
import subprocess
import sys

import pytest

import pysolver

from helpers import DECKS

SEED3 = (DECKS / "particle_between_lines.xml").read_text()


def test_xml_encoding_declaration_is_honoured(tmp_path):
    path = tmp_path / "latin.xml"
    path.write_bytes(SEED3.replace('<?xml version="1.0"?>',
                                   '<?xml version="1.0" encoding="ISO-8859-1"?>')
                     .replace('label="Enforce 1+x&lt;=z"', 'label="caf\xe9"').encode("latin-1"))
    model = pysolver.load(path)
    assert model.penalties[1].label == "caf\xe9"
    assert model.run().success


def test_undeclared_non_utf8_bytes_are_a_deck_error(tmp_path):
    path = tmp_path / "bad.xml"
    path.write_bytes(SEED3.replace('label="Enforce 1+x&lt;=z"', 'label="caf\xe9"')
                     .encode("latin-1"))
    with pytest.raises(pysolver.DeckError, match="not valid utf-8 text .* declare its encoding") \
            as info:
        pysolver.load(path)
    assert info.value.line == 14


def test_dtd_and_entities_are_refused():
    text = SEED3.replace('<?xml version="1.0"?>',
                         '<?xml version="1.0"?>\n<!DOCTYPE m [<!ENTITY e "DX(10)+1000">]>')
    text = text.replace('expr1="DX(10)"', 'expr1="&e;"')
    with pytest.raises(pysolver.DeckError, match="DOCTYPE"):
        pysolver.loads(text)


@pytest.mark.parametrize("expr", ["+".join(["DX(10)"] * 1000), "(" * 200 + "1" + ")" * 200,
                                  "-" * 3000 + "1"])
def test_deep_expressions_are_deck_errors(expr):
    with pytest.raises(pysolver.DeckError, match="nests deeper than 120 levels"):
        pysolver.loads(SEED3.replace('expr1="DX(10)"', f'expr1="{expr}"'))


def test_a_sum_of_100_terms_parses_and_runs():
    text = SEED3.replace('expr1="DX(10)"', f'expr1="{"+".join(["DX(10)"] * 100)}"')
    res = pysolver.loads(text).run(integr_tol=1e-4)
    assert res.success and abs(res.request(1)[-1, 0] - 100 * res.y[-1, 0]) < 1e-9


@pytest.mark.parametrize("expr,match", [
    ("1E999", "the number 1E999 is too large"), ("10**400", r"\(10 \*\* 400\) is inf"),
    ("1D400", "the number 1D400 is too large"), ("1/0", r"\(1 / 0\) is inf"),
    ("EXP(1000)", r"EXP\(1000\) is inf"), ("LOG(-1)", "is nan"), ("SQRT(-1)", "is nan"),
    ("ACOS(2)", r"ACOS\(2\) is nan"), ("MOD(1,0)", r"MOD\(1, 0\) is nan"),
    ("0/0", r"\(0 / 0\) is nan"),
])
def test_non_finite_constants_are_deck_errors(expr, match):
    with pytest.raises(pysolver.DeckError, match=match) as info:
        pysolver.loads(SEED3.replace('expr="1+dx(10)-dz(10)"', f'expr="{expr}"'))
    assert info.value.attribute == "expr" and info.value.element == "Force_Penalty"


@pytest.mark.parametrize("old,new", [('end_time="3.0"', 'end_time="1e308"'),
                                     ('print_interval="0.005"', 'print_interval="1e-300"')])
def test_impossible_output_grids_are_deck_errors(old, new):
    with pytest.raises(pysolver.DeckError, match="output rows; at most 1e\\+09 per command"):
        pysolver.loads(SEED3.replace(old, new))


def test_outputs_past_the_memory_budget_stop_before_allocating():
    """end_time 1e6 every 5 ms: 2e8 rows would need 30 GiB; the run stops at once."""
    res = pysolver.loads(SEED3.replace('end_time="3.0"', 'end_time="1e6"')).run()
    assert not res.success and res.status == -500
    assert "2e+08 output rows" in res.message and "PYSOLVER_OUTPUT_BUDGET" in res.message
    assert len(res.t) == 1                          # the initial row, nothing else


def test_max_num_steps_in_e_notation():
    text = SEED3.replace('integr_tol="1e-6"', 'integr_tol="1e-6" max_num_steps="1e8"')
    assert pysolver.loads(text).transient.max_num_steps == 100_000_000


def test_check_of_a_folder_exits_2(tmp_path):
    import os
    import pathlib
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(pysolver.__file__).parents[1]))
    out = subprocess.run([sys.executable, "-m", "pysolver.cli", "check", str(tmp_path)],
                         capture_output=True, text=True, cwd=tmp_path, env=env)
    assert out.returncode == 2 and "is a folder, not a deck file" in out.stderr
    assert "Traceback" not in out.stderr


def test_ctrl_c_stops_a_run_and_the_cli_writes_the_rows(tmp_path):
    """SIGINT to `pysolver run` on a long deck (the stiff pendulum for 1e5 s): it stops (the C
    kernel's handler ends the run at its next residual), exits 130, and writes the rows computed so far, the
    CSV agreeing with stats.json."""
    import json
    import os
    import pathlib
    import signal
    import time
    deck = tmp_path / "long.xml"
    text = (DECKS / "stiff_penalty_pendulum.xml").read_text()
    text = re.sub(r'end_time="[^"]*"', 'end_time="100000.0"', text)
    deck.write_text(text.replace("<Param_Transient", '<Param_Transient max_num_steps="1e9"'))
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(pysolver.__file__).parents[1]))
    proc = subprocess.Popen([sys.executable, "-m", "pysolver.cli", "run", str(deck), "-o",
                             str(tmp_path / "out"), "-q", "--no-plot"], cwd=tmp_path, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # interrupted once it is integrating: its streamed CSV holds rows (not after a fixed
    # sleep, which a loaded machine can spend importing)
    csv = tmp_path / "out" / "requests.csv"
    deadline = time.monotonic() + 300.0
    while proc.poll() is None and time.monotonic() < deadline and not (
            csv.exists() and csv.read_text().count("\n") > 12):
        time.sleep(0.05)
    assert proc.poll() is None
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)         # not the 1e5 s the run would take
    assert proc.returncode == 130, err[-2000:]
    stats = json.loads((tmp_path / "out" / "stats.json").read_text())
    assert not stats["success"] and stats["message"].startswith("interrupted at t = ")
    rows = (tmp_path / "out" / "requests.csv").read_text().strip().splitlines()[1:]
    assert len(rows) == stats["stats"]["outputs"] > 10
    t_last = float(rows[-1].split(",")[0])
    assert 0.0 < t_last < 100000.0
    assert "Traceback" not in err


def test_check_runs_the_output_budget_check_a_run_makes(tmp_path):
    """end_time 1e6 every 5 ms loads (the grid is below 1e9 rows), but a run would stop at once
    with status -500; check says so, with the Simulate command's line, and exits 2."""
    import os
    import pathlib
    deck = tmp_path / "long.xml"
    deck.write_text(SEED3.replace('end_time="3.0"', 'end_time="1e6"'))
    with pytest.raises(pysolver.DeckError, match=r"2e\+08 output rows \(29.8 GiB\)") as info:
        pysolver.load(deck).check()
    assert info.value.element == "Simulate" and info.value.line == 22
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(pysolver.__file__).parents[1]))
    out = subprocess.run([sys.executable, "-m", "pysolver.cli", "check", str(deck)],
                         capture_output=True, text=True, cwd=tmp_path, env=env)
    assert out.returncode == 2 and "output budget" in out.stderr and "Traceback" not in out.stderr
    pysolver.loads(SEED3).check()                     # a deck that fits passes


def test_run_with_no_plot_does_not_import_matplotlib(tmp_path):
    """`pysolver run` imported matplotlib for every deck (most of its 1.7-2.5 s); with
    --no-plot it is not imported at all, and no PNG is written."""
    import os
    import pathlib
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(pysolver.__file__).parents[1]))
    code = ("import sys; from pysolver.cli import main; "
            f"rc = main(['run', {str(DECKS / 'particle_between_lines.xml')!r}, '-o', 'out', "
            "'-q', '--no-plot']); print(rc, 'matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=tmp_path, env=env)
    assert out.stdout.strip().splitlines()[-1] == "0 False", out.stderr[-2000:]
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["requests.csv", "scene.html",
                                                                    "stats.json"]
