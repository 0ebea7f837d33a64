"""Where a relative usrsub_dll_name / script_name / ROUTINE library is found (trial 45): in the
deck's folder first (MotionSolve's rule), then in the current directory, which is the only
folder of a deck given as text."""
import numpy as np
import pytest

import pysolver

from scenes import SPRING_PY, SPRING_SFOSUB, SPRING_XML, usersub_library

#: Which library ran shows in the motion: the deck's (10 N/m) or another folder's (40 N/m).
PY = SPRING_PY.format(routine="sx.so::SFOSUB")


def _xml(lib):
    return SPRING_XML.format(usersub=f'usrsub_dll_name="{lib}"')


@pytest.fixture(scope="module")
def folders(tmp_path_factory):
    """deck/ holds the deck and its sx.so (k = 10); other/ another sx.so (k = 40) and
    only.so (k = 40), which the deck's folder has not."""
    root = tmp_path_factory.mktemp("paths")
    deck, other = root / "deck", root / "other"
    deck.mkdir()
    other.mkdir()
    if usersub_library(deck, SPRING_SFOSUB % "10.0", "sx") is None:
        pytest.skip("no C compiler")
    usersub_library(other, SPRING_SFOSUB % "40.0", "sx")
    usersub_library(other, SPRING_SFOSUB % "40.0", "only")
    (deck / "spring.xml").write_text(_xml("sx.so"))
    (deck / "spring_only.xml").write_text(_xml("only.so"))
    (deck / "spring.py").write_text(PY)
    return deck, other


def _check(res, lib, k):
    assert res.success, res.message
    (how,) = res.meta["usersubs"].values()
    assert how.startswith(f"USER(10) -> SFOSUB ({lib}): C library {lib}, called from")
    t = np.asarray(res.t)
    np.testing.assert_allclose(res.request(1)[:, 0], 1 + np.cos(np.sqrt(k) * t), atol=1e-5)


@pytest.mark.parametrize("name", ["spring.xml", "spring.py"])
def test_the_decks_own_library_wins_over_the_current_directorys(folders, monkeypatch, name):
    deck, other = folders
    monkeypatch.chdir(other)
    _check(pysolver.load(str(deck / name)).run(integr_tol=1e-9), deck / "sx.so", 10)


def test_a_library_not_beside_the_deck_is_found_in_the_current_directory(folders, monkeypatch):
    deck, other = folders
    monkeypatch.chdir(other)
    _check(pysolver.load(str(deck / "spring_only.xml")).run(integr_tol=1e-9),
           other / "only.so", 40)


@pytest.mark.parametrize("fmt", ["xml", "py"])
def test_a_deck_given_as_text_uses_the_current_directory(folders, monkeypatch, fmt):
    deck, other = folders
    monkeypatch.chdir(other)
    text = _xml("sx.so") if fmt == "xml" else PY
    _check(pysolver.loads(text, fmt=fmt).run(integr_tol=1e-9), other / "sx.so", 40)


def test_a_missing_library_lists_the_folders_in_order(folders, monkeypatch):
    deck, other = folders
    monkeypatch.chdir(other)
    monkeypatch.delenv("PYSOLVER_USERSUB_DIR", raising=False)
    (deck / "spring_none.xml").write_text(_xml("none.so"))
    with pytest.raises(pysolver.DeckError) as err:
        pysolver.load(str(deck / "spring_none.xml"))
    assert str(err.value) == (f"{deck}/spring_none.xml:7, Force_Scalar_TwoBody id=1, attribute "
                              f"'usrsub_dll_name': library 'none.so' not found (looked in: "
                              f"{deck}/none.so, {other}/none.so)")
