"""Elements that do not move anything are kept, not refused: Post_Graphic (for the 3-D view)
and the output settings (ResOutput, H3DOutput)."""
import numpy as np
import pytest

import pysolver
from pysolver import DeckError

from helpers import ROOT

PENDULUM = (ROOT / "decks" / "joints" / "pendulum_revolute.xml").read_text()
GRAPHICS = ('<Post_Graphic id="1" type="Cylinder" center_marker_id="20" radius="0.05" '
            'length="0.2" refinement_level="2" ends_type="CLOSED" color="255:0:0"/>'
            '<Post_Graphic id="2" type="BoxDefinedFromCenter" center_marker_id="21" '
            'length_x="0.1" length_y="0.2" length_z="0.3" label="block"/>')


def test_graphics_and_output_settings_are_kept_and_change_nothing():
    """Two graphics with their attributes as written, both output commands' settings; the run
    equals the deck without them, to the bit."""
    text = PENDULUM.replace("</Model>", GRAPHICS + "</Model>").replace(
        "</MotionSolve>", '<ResOutput mrf_file="TRUE" angle_type="YPR"/>'
                          '<H3DOutput save="TRUE"/></MotionSolve>')
    model = pysolver.loads(text)
    g = model.graphics
    assert (g[1].type, g[1].attrs["radius"], g[1].attrs["center_marker_id"]) == \
        ("Cylinder", "0.05", "20")
    assert (g[2].type, g[2].label, g[2].attrs["length_z"]) == ("BoxDefinedFromCenter",
                                                               "block", "0.3")
    assert model.output_settings == {"ResOutput": {"mrf_file": "TRUE", "angle_type": "YPR"},
                                     "H3DOutput": {"save": "TRUE"}}
    a, b = model.run(), pysolver.loads(PENDULUM).run()
    np.testing.assert_array_equal(a.request(1), b.request(1))


def test_the_graphics_statement(tmp_path):
    deck = tmp_path / "g.py"
    deck.write_text("from pysolver.msolve import *\nPART(1, GROUND=True)\nMARKER(1, PART=1)\n"
                    "MARKER(9, PART=2, QP=[1, 0, 0])\nPOINT_MASS(2, MASS=1, CM=9)\n"
                    "GRAPHICS(1, TYPE='Sphere', CENTER_MARKER_ID=9, RADIUS=0.1)\n")
    assert pysolver.load(deck).graphics[1].attrs == {"center_marker_id": "9", "radius": "0.1"}


@pytest.mark.parametrize("attrs, attribute, words", [
    ('type="Cylinder" center_marker_id="77"', "center_marker_id", "marker 77 does not exist"),
    ('type="Sphere" center_marker_id="x"', "center_marker_id", "expected a marker id"),
    ('center_marker_id="20"', "type", "required"),
])
def test_a_graphic_naming_a_missing_marker_is_a_deck_error(attrs, attribute, words):
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(PENDULUM.replace("</Model>", f'<Post_Graphic id="3" {attrs}/></Model>'))
    assert (err.value.element, err.value.attribute) == ("Post_Graphic", attribute)
