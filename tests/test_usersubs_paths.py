"""Where a relative usrsub_dll_name / script_name / ROUTINE library is found (trial 45): in the
deck's folder first (MotionSolve's rule), then in the current directory, which is the only
folder of a deck given as text."""
import numpy as np
import pytest

import pysolver

from scenes import usersub_library

#: The same SFOSUB with another stiffness: which library ran shows in the motion.
SFOSUB = r'''#include "pysolver_usersub.h"
void SFOSUB(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int m = (int)par[0], err;
  double x;
  c_sysfnc("DX", &m, 1, &x, &err);
  *value = -%s * (x - 1.0);
}
'''

XML = '''<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="10" body_id="2" pos_x="2"/>
<Body_Point id="2" cg_id="10" mass="1.0"/>
<Force_Scalar_TwoBody id="1" type="Force" i_marker_id="10" j_marker_id="1"
  usrsub_dll_name="{lib}" usrsub_param_string="USER(10)"/>
<Post_Request id="1" expr1="DX(10)"/>
</Model><Simulate analysis_type="Transient" end_time="1" print_interval="0.1"/></MotionSolve>
'''

PY = '''from pysolver.msolve import *
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[2, 0, 0])
POINT_MASS(2, MASS=1.0, CM=10)
SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="USER(10)", ROUTINE="sx.so::SFOSUB")
REQUEST(1, F1="DX(10)")
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.1)
'''


@pytest.fixture(scope="module")
def folders(tmp_path_factory):
    """deck/ holds the deck and its sx.so (k = 10); other/ another sx.so (k = 40) and
    only.so (k = 40), which the deck's folder has not."""
    root = tmp_path_factory.mktemp("paths")
    deck, other = root / "deck", root / "other"
    deck.mkdir()
    other.mkdir()
    if usersub_library(deck, SFOSUB % "10.0", "sx") is None:
        pytest.skip("no C compiler")
    usersub_library(other, SFOSUB % "40.0", "sx")
    usersub_library(other, SFOSUB % "40.0", "only")
    (deck / "spring.xml").write_text(XML.format(lib="sx.so"))
    (deck / "spring_only.xml").write_text(XML.format(lib="only.so"))
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
    text = XML.format(lib="sx.so") if fmt == "xml" else PY
    _check(pysolver.loads(text, fmt=fmt).run(integr_tol=1e-9), other / "sx.so", 40)


def test_a_missing_library_lists_the_folders_in_order(folders, monkeypatch):
    deck, other = folders
    monkeypatch.chdir(other)
    monkeypatch.delenv("PYSOLVER_USERSUB_DIR", raising=False)
    (deck / "spring_none.xml").write_text(XML.format(lib="none.so"))
    with pytest.raises(pysolver.DeckError) as err:
        pysolver.load(str(deck / "spring_none.xml"))
    assert str(err.value) == (f"{deck}/spring_none.xml:7, Force_Scalar_TwoBody id=1, attribute "
                              f"'usrsub_dll_name': library 'none.so' not found (looked in: "
                              f"{deck}/none.so, {other}/none.so)")
