"""A C user subroutine library rebuilt at the same path is the new one in the same process
(pysolver.build.userlib): dlopen would hand back the old code, with no sign of it."""
import numpy as np
import pytest

import pysolver

from scenes import LINES_C, lines_deck, usersub_library


def _final_x(text):
    res = pysolver.loads(text, fmt="py").run()
    assert res.success, res.message
    return res.request(1)[-1, :2]


def test_a_rebuilt_library_runs_its_new_code(tmp_path):
    """Seed example 3's lines as a C routine; rebuilt with both lines lifted by 5 mm, the
    particle comes to rest 5 mm higher; rebuilt as it was, where it was."""
    text, _ = lines_deck("c", tmp_path)
    if text is None:
        pytest.skip("no C compiler")
    first = _final_x(text)
    lifted = LINES_C.replace("*value = 1.0 + par[1] * p[0] - p[2];",
                             "*value = 6.0 + par[1] * p[0] - p[2];")
    assert lifted != LINES_C
    usersub_library(tmp_path, lifted)                  # the same path, subs.so
    second = _final_x(text)
    assert second[1] == pytest.approx(first[1] + 5.0, abs=1e-3)
    usersub_library(tmp_path, LINES_C)
    np.testing.assert_array_equal(_final_x(text), first)


def test_a_symlink_moved_to_a_rebuilt_library(tmp_path):
    """The library is opened by its real path: `subs.so -> subs.so.1` relinked to a rebuilt
    `subs2.so` is the new code (dlopen of the link's name handed back the old)."""
    text, _ = lines_deck("c", tmp_path)
    if text is None:
        pytest.skip("no C compiler")
    link = tmp_path / "subs.so"
    link.rename(tmp_path / "subs.so.1")
    link.symlink_to(tmp_path / "subs.so.1")
    first = _final_x(text)
    usersub_library(tmp_path, LINES_C.replace("*value = 1.0 + par[1] * p[0] - p[2];",
                                              "*value = 6.0 + par[1] * p[0] - p[2];"), "subs2")
    link.unlink()
    link.symlink_to(tmp_path / "subs2.so")
    assert _final_x(text)[1] == pytest.approx(first[1] + 5.0, abs=1e-3)
