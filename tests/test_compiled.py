"""The public compiled model (issue 23 item 2): Model.compile() owns the kernel and the caches of
runs; Model.run(params=...) changes numbers for one run, by the sweep's paths, without a
recompile, equal to the deck edited by hand, and the next run has the deck's values again."""
import numpy as np
import pytest

import pysolver

from helpers import DECKS

SEED3 = (DECKS / "particle_between_lines.xml").read_text()
CHANGES = {"Body_Point/2/mass": 2.0, "Force_Penalty/1/penalty": 2.5e4,
           "Reference_Marker/10/pos_x": 90.0, "Force_Gravity/grav_z": -5000.0}
EDITED = (SEED3.replace('mass="1.0"', 'mass="2.0"')
          .replace('pos_x="100"', 'pos_x="90"'))


def _edited_by_hand():
    text = EDITED
    first = text.index('penalty="', text.index('<Force_Penalty id="1"'))
    end = text.index('"', first + len('penalty="'))
    text = text[:first] + 'penalty="2.5e4' + text[end:]
    text = text.replace('grav_z="-9810"', 'grav_z="-5000"')
    assert text.count("2.5e4") == 1 and 'grav_z="-5000"' in text
    return pysolver.loads(text)


def test_params_equal_the_deck_edited_by_hand_and_do_not_stay():
    model = pysolver.loads(SEED3)
    plain = model.run()
    changed = model.run(params=CHANGES)
    ref = _edited_by_hand().run()
    assert changed.success and ref.success
    assert changed.stats["steps"] == ref.stats["steps"]
    np.testing.assert_allclose(changed.y, ref.y, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(changed.request(1), ref.request(1), rtol=1e-12, atol=1e-12,
                               equal_nan=True)
    again = model.run()                           # the deck's values again, to the bit
    assert np.array_equal(again.y, plain.y) and again.stats == plain.stats
    assert not np.allclose(changed.y[-1], plain.y[-1])


def test_params_compile_nothing_new():
    model = pysolver.loads(SEED3)
    compiled = model.compile()
    model.run()
    model.run(params=CHANGES)
    assert model.compile() is compiled and compiled.kernel is model.compile().kernel
    assert model.compile("tapes") is not compiled
    assert model.compile("tapes").kernel.codegen["kernel"] == "tapes"


def test_params_of_param_transient_are_run_options():
    model = pysolver.loads(SEED3)
    a = model.run(params={"Param_Transient/integr_tol": 1e-7})
    b = model.run(integr_tol=1e-7)
    assert np.array_equal(a.y, b.y) and a.meta["options"]["integr_tol"] == 1e-7
    assert model.run().meta["options"]["integr_tol"] == model.transient.integr_tol != 1e-7


@pytest.mark.parametrize("params, match", [
    ({"Body_Point/7/mass": 1.0}, r"sweep parameter .Body_Point/7/mass.: no Body_Point 7 in this "
                                  r"model \(its Body_Points: 2\)"),
    ({"Force_Penalty/1/penalty": -1e4}, r"got -10000; expected a value > 0"),
    ({"Body_Point/2/mass": "heavy"}, r"got 'heavy'; expected a real number"),
])
def test_bad_params_are_deck_errors_and_change_nothing(params, match):
    model = pysolver.loads(SEED3)
    plain = model.run()
    with pytest.raises(pysolver.DeckError, match=match):
        model.run(params=params)
    assert np.array_equal(model.run().y, plain.y)


def test_a_compiled_model_runs_like_the_model():
    model = pysolver.loads(SEED3)
    compiled = model.compile()
    a, b = compiled.run(), model.run()
    assert np.array_equal(a.y, b.y) and a.message == b.message
    assert "Force_Penalty/1/penalty" in compiled.parameters.paths()


def test_a_loaded_model_reads_only_and_says_how_to_change_a_number():
    """Setting model.bodies[2].mass used to be taken silently and ignored by the next run
    (the kernel was compiled); now every assignment to a loaded model is refused, saying how
    to change a number for one run."""
    model = pysolver.loads(SEED3)
    plain = model.run()
    for target, name, value in ((model.bodies[2], "mass", 2.0), (model, "gravity", None),
                                (model.penalties[1], "penalty", 1.0)):
        with pytest.raises(AttributeError, match=r"cannot set \w+\.\w+: a loaded Model is what "
                           r"its deck says and does not change: give a number for one run "
                           r"with model.run\(params="):
            setattr(target, name, value)
    with pytest.raises(ValueError, match="read-only"):
        model.bodies[2].vel[0] = 5.0            # arrays too
    with pytest.raises(ValueError, match="read-only"):
        model.gravity[2] = 0.0
    assert np.array_equal(model.run().y, plain.y)


def test_compiling_leaves_the_loaded_model_as_it_was(tmp_path):
    """User subroutines resolve into the compiled scene, not into the loaded model: its
    Force_Penalty keeps expr None and its routine's text; the run reports how it ran."""
    script = tmp_path / "bead.py"
    script.write_text("import math\n\n\ndef PFOSUB(id, time, par, npar, dflag, iflag):\n"
                      "    [x, e] = py_sysfnc('DX', [9])\n    [y, e] = py_sysfnc('DY', [9])\n"
                      "    return y - math.cosh(x)\n")
    text = (DECKS / "catenary_bead.xml").read_text().replace(
        'type="EXPRESSION"\n                   expr="dy(9) - cosh(dx(9))"',
        f'type="USERSUB" script_name="{script}" usrsub_param_string="USER(9)"')
    model = pysolver.loads(text)
    res = model.run()
    assert res.success and "traced into the kernel" in res.meta["usersubs"]["Force_Penalty 1"]
    assert model.penalties[1].expr is None and model.penalties[1].usersub.untraced is None
    assert model.compile().model.penalties[1].expr is not None
