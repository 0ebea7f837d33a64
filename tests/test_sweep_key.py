"""A sweep's resume key covers everything a row depends on (docs/batch.md, "Resuming"): the
Simulate command ``load(deck, simulate=...)`` puts in, what a Python deck built and the
user's modules it imports, and the environment settings that change results; a worker kept
from an earlier sweep runs only in the environment it was started in (trial 44, defects 2
and 3)."""
import os
import sys

import pytest

import pysolver
from pysolver.batch.case import fingerprint

from helpers import DECKS

DECK = DECKS / "particle_between_lines.xml"
PEN = "Force_Penalty/1/penalty"
SHORT = {"analysis_type": "TRANSIENT", "end_time": 0.1, "print_interval": 0.01}


def test_a_simulate_override_is_part_of_the_key(tmp_path):
    """Trial 44's repro: rows of a sweep of the deck loaded with a 0.1 s command are not the
    rows of the deck's own 3 s command; each sweep resumes its own."""
    cases = pysolver.grid({PEN: [5e3, 1e4]})
    outs = {"z_end": "final:request/1/2"}
    study = tmp_path / "study"
    short = pysolver.sweep(pysolver.load(DECK, simulate=SHORT), cases, processes=0,
                           outputs=outs, directory=study)
    full = pysolver.sweep(pysolver.load(DECK), cases, processes=0, outputs=outs,
                          directory=study)
    assert [r["resumed"] for r in full.rows] == [False, False]
    assert full.result(0).t[-1] == 3.0 and short.result(0).t[-1] == 0.1
    for row, case in zip(full.rows, cases):
        ref = pysolver.load(DECK).run(params=case)
        assert row["z_end"] == ref.request(1)[-1, 1]
    for model in (pysolver.load(DECK, simulate=SHORT), pysolver.load(DECK)):
        again = pysolver.sweep(model, cases, processes=0, outputs=outs, directory=study)
        assert [r["resumed"] for r in again.rows] == [True, True]


@pytest.mark.parametrize("name, value", [("PYSOLVER_PLANAR", "off"), ("PYSOLVER_HELD", "off"),
                                         ("PYSOLVER_KERNEL", "tapes"), ("CC", "clang"),
                                         ("PYSOLVER_COMPILE_TIMEOUT", "5")])
def test_environment_settings_that_change_results_are_in_the_key(name, value, monkeypatch):
    """Each setting that changes a run's numbers changes the key; one that does not (the
    output budget) leaves it."""
    for unset in ("PYSOLVER_PLANAR", "PYSOLVER_HELD", "PYSOLVER_KERNEL", "CC",
                  "PYSOLVER_COMPILE_TIMEOUT", "PYSOLVER_OUTPUT_BUDGET"):
        monkeypatch.delenv(unset, raising=False)
    model = pysolver.load(DECK)
    base = fingerprint(model, {})
    monkeypatch.setenv("PYSOLVER_OUTPUT_BUDGET", "1e9")
    assert fingerprint(model, {}) == base
    monkeypatch.setenv(name, value)
    assert fingerprint(model, {}) != base


def test_a_kept_worker_runs_only_in_its_own_environment(monkeypatch):
    """A worker kept idle after a sweep is reused by the next sweep in the same environment,
    and not after PYSOLVER_PLANAR changed: the new sweep's worker reads the new setting."""
    monkeypatch.delenv("PYSOLVER_PLANAR", raising=False)
    outs = {"pid": lambda res: float(os.getpid()),
            "planar": lambda res: float(__import__("pysolver.settings").settings.planar())}
    model = pysolver.load(DECK, simulate=SHORT)
    first = pysolver.sweep(model, [{PEN: 1e4}], processes=1, outputs=outs)
    same = pysolver.sweep(model, [{PEN: 2e4}], processes=1, outputs=outs)
    assert same.rows[0]["pid"] == first.rows[0]["pid"] and first.rows[0]["planar"] == 1.0
    monkeypatch.setenv("PYSOLVER_PLANAR", "off")
    other = pysolver.sweep(model, [{PEN: 2e4}], processes=1, outputs=outs)
    assert other.rows[0]["pid"] != first.rows[0]["pid"] and other.rows[0]["planar"] == 0.0


#: particle_between_lines.py with line 2's penalty from a settings module beside it and line
#: 1's offset from a package of its own (whose __init__ takes it from a submodule).
PY_DECK = (DECKS / "particle_between_lines.py").read_text().replace(
    "from pysolver.msolve import *\n",
    "from pysolver.msolve import *\nimport os, sys\n"
    "sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))\n"
    "from trial44_settings import PEN2\nimport trial44_geometry\n").replace(
    'FUNCTION="1-DX(10)-DZ(10)", PENALTY=1e4', 'FUNCTION="1-DX(10)-DZ(10)", PENALTY=PEN2').replace(
    'FUNCTION="1+DX(10)-DZ(10)"', 'FUNCTION=f"{trial44_geometry.OFFSET}+DX(10)-DZ(10)"').replace(
    "END=3.0", "END=1.0")


@pytest.fixture
def py_deck(tmp_path, monkeypatch):
    """The deck, its modules, and a clean slate: sys.path and the modules imported restored."""
    monkeypatch.setattr(sys, "path", list(sys.path))
    (tmp_path / "deck.py").write_text(PY_DECK)
    (tmp_path / "trial44_settings.py").write_text("PEN2 = 1e4\n")
    (tmp_path / "trial44_geometry").mkdir()
    (tmp_path / "trial44_geometry" / "__init__.py").write_text("from .shape import OFFSET\n")
    (tmp_path / "trial44_geometry" / "shape.py").write_text("OFFSET = 1.0\n")
    yield tmp_path
    for name in ("trial44_settings", "trial44_geometry", "trial44_geometry.shape"):
        sys.modules.pop(name, None)


def _forget_modules():
    """What a new Python session sees: the modules imported afresh."""
    for name in ("trial44_settings", "trial44_geometry", "trial44_geometry.shape"):
        sys.modules.pop(name, None)


def test_a_python_decks_own_modules_are_in_the_key(py_deck):
    """Trial 44's repro: editing the settings module a Python deck imports, or the submodule
    of the package it imports, makes a resumed sweep run the cases again (with the edited
    numbers, as a fresh load and run give); a code-only edit does too; nothing edited, the rows
    are reused."""
    cases, outs = [{PEN: 1e4}], {"x": "final:request/1/1"}
    deck, study = py_deck / "deck.py", py_deck / "study"

    def sweep():
        _forget_modules()
        sw = pysolver.sweep(deck, cases, processes=1, directory=study, outputs=outs)
        _forget_modules()
        ref = pysolver.load(deck).run(params=cases[0]).request(1)[-1, 0]
        assert sw.rows[0]["status"] == "ok" and sw.rows[0]["x"] == ref
        return sw.rows[0]

    first = sweep()
    assert sweep()["resumed"] is True
    (py_deck / "trial44_settings.py").write_text("PEN2 = 3e4\n")
    edited = sweep()
    assert edited["resumed"] is False and edited["x"] != first["x"]
    assert sweep()["resumed"] is True
    (py_deck / "trial44_geometry" / "shape.py").write_text("OFFSET = 2.0\n")
    assert sweep()["resumed"] is False
    (py_deck / "trial44_settings.py").write_text("PEN2 = 3e4\n\n\ndef unused():\n    pass\n")
    assert sweep()["resumed"] is False
    assert sweep()["resumed"] is True
    model = pysolver.load(deck)
    assert [os.path.basename(p) for p, _ in model.source.modules] == [
        "__init__.py", "shape.py", "trial44_settings.py"]


def test_a_module_edited_after_this_session_imported_it_is_named(py_deck):
    """In one session Python imports a module once: loading the deck again after its module
    was edited warns that the deck still runs the module as first imported."""
    pysolver.load(py_deck / "deck.py")
    (py_deck / "trial44_settings.py").write_text("PEN2 = 3e4\n")
    with pytest.warns(pysolver.DeckWarning, match="module trial44_settings .* changed since "
                      "this session imported it, and Python imports a module once"):
        model = pysolver.load(py_deck / "deck.py")
    assert model.penalties[2].penalty == 1e4         # the module as first imported


def test_numbers_a_python_deck_reads_from_a_file_are_in_the_key(tmp_path):
    """What a Python deck built is in the key, wherever its numbers came from (a data file
    here, not a module)."""
    (tmp_path / "pen.txt").write_text("10000\n")
    (tmp_path / "deck.py").write_text(PY_DECK.replace(
        "from trial44_settings import PEN2\nimport trial44_geometry\n",
        "PEN2 = float(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "
        "'pen.txt')).read())\n").replace('f"{trial44_geometry.OFFSET}+', '"1+'))
    before = fingerprint(pysolver.load(tmp_path / "deck.py"), {})
    assert fingerprint(pysolver.load(tmp_path / "deck.py"), {}) == before
    (tmp_path / "pen.txt").write_text("30000\n")
    assert fingerprint(pysolver.load(tmp_path / "deck.py"), {}) != before
