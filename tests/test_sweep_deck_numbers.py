"""A case's numbers are the deck's own (docs/batch.md, "The paths a case may set"): a marker's
pos_* in its rm_id's frame (an Adams QP in its part's frame or RM's), v_ic_* along vm_id's
axes, w_ic_* along wm_id's (an Adams or msolve PART's WX.. along its CM marker's). A case is
therefore the deck edited by hand, bit for bit, in every form."""
import pathlib

import numpy as np
import pytest

import pysolver

ROOT = pathlib.Path(__file__).resolve().parents[1]
SHORT = {"analysis_type": "TRANSIENT", "end_time": 0.2, "print_interval": 0.01}

#: The spinning top in each form: its file, format, and how its tip's place (rm_id / RM = the
#: cg marker, tilted 0.3 rad), its cg's place and its spin (along the cg marker) are written.
TOP = {
    "xml": ("decks/spinning_top.xml", "xml", {
        "tip": ('pos_z="-0.1" rm_id="20"', 'pos_z="{}" rm_id="20"'),
        "cg": ('pos_z="0.09553364891256061"', 'pos_z="{}"'),
        "spin": ('w_ic_z="200.0"', 'w_ic_z="{}"')}),
    "statements": ("decks/spinning_top.py", "py", {
        "tip": ("QP=[0, 0, -0.1], RM=20", "QP=[0, 0, {}], RM=20"),
        "cg": ("0.09553364891256061]", "{}]"),
        "spin": ("WZ=200.0", "WZ={}")}),
    "adams": ("decks/forms/adams/spinning_top.adm", "adm", {
        "tip": ("QP = 0.0, 0.0, -0.1, RM = 20", "QP = 0.0, 0.0, {}, RM = 20"),
        "cg": ("0.09553364891256061\n", "{}\n"),
        "spin": ("WZ = 200.0", "WZ = {}")}),
    "classes": ("decks/forms/msolve/spinning_top.py", "py", {
        "tip": ("qp=[0.0, 0.0, -0.1]", "qp=[0.0, 0.0, {}]"),
        "cg": ("0.09553364891256061]", "{}]"),
        "spin": ("wz=200.0", "wz={}")}),
}
TOP_PATHS = {"tip": ("Reference_Marker/21/pos_z", -0.1, -0.05),
             "cg": ("Reference_Marker/20/pos_z", 0.09553364891256061, 0.12),
             "spin": ("Body_Rigid/2/w_ic_z", 200.0, 150.0)}


def _same_run(a, b):
    assert (a.success, a.status, a.message) == (b.success, b.status, b.message)
    assert np.array_equal(a.t, b.t) and np.array_equal(a.y, b.y)
    for rid in b.request_ids:
        assert np.array_equal(a.request(rid), b.request(rid), equal_nan=True)


@pytest.mark.parametrize("form", list(TOP))
def test_a_case_is_the_spinning_top_edited_by_hand(form):
    """The tip's pos_z (in the tilted cg marker's frame), the cg's pos_z (the tip moves with
    it, as in the deck) and the spin w_ic_z (about the symmetry axis): each path's deck value
    is the number written in the deck, and each case runs as the deck edited by hand, bit for
    bit; a run without a case is the deck again."""
    file, fmt, edits = TOP[form]
    text = (ROOT / file).read_text()
    model = pysolver.loads(text, fmt=fmt, file=str(ROOT / file), simulate=SHORT)
    params = model.compile().parameters
    plain = model.run(progress=False)
    for what, (old, new) in edits.items():
        path, deck, value = TOP_PATHS[what]
        assert params._get(path) == deck
        assert text.count(old) == 1
        case = model.run(progress=False, params={path: value})
        by_hand = pysolver.loads(text.replace(old, new.format(value)), fmt=fmt,
                                 file=str(ROOT / file), simulate=SHORT).run(progress=False)
        _same_run(case, by_hand)
    # the tip stays on the symmetry axis 0.05 below the cg: the gap at the pivot is 0.05 m
    assert case.success and np.isclose(
        pysolver.loads(text, fmt=fmt, file=str(ROOT / file), simulate=SHORT)
        .run(progress=False, params={"Reference_Marker/21/pos_z": -0.05}).request(1)[0, 3],
        0.05, atol=1e-12)
    _same_run(model.run(progress=False), plain)


#: A part whose frame is moved and turned (QG, REULER): its markers' QP are in its frame, a
#: chain of RM markers (22 in 21's frame, 23 in 22's), VX along ground marker 2's axes (VM),
#: WX.. along the CM marker's.
TURNED_PART = """turned part
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 0, 0, 1, REULER = 45D, 0, 0
PART/2, MASS = 1.0, CM = 20, IP = 1, 2, 3, QG = 1, 0.5, 0, REULER = 30D, 20D, 0
, WX = 1, WZ = 2, VX = 0.5, VM = 2
MARKER/20, PART = 2, QP = 0.1, 0, 0
MARKER/21, PART = 2, QP = 0.2, 0, 0.1, REULER = 0, 90D, 0
MARKER/22, PART = 2, QP = 0, 0, 0.3, RM = 21
MARKER/23, PART = 2, QP = 0.1, 0.1, 0.3, RM = 22
SFORCE/1, TRANSLATION, I = 23, J = 1, FUNCTION = -10*(DM(23,1)-1)
SFORCE/2, TRANSLATION, I = 21, J = 1, FUNCTION = -5*(DM(21,1)-1)
REQUEST/1, F1 = DX(20)\\, F2 = DX(21)\\, F3 = DY(22)\\, F4 = DZ(23)\\, F5 = WX(20)\\, F6 = VX(20)
INTEGRATOR/ERROR = 1e-08
END
"""

TURNED_EDITS = [
    ({"Reference_Marker/21/pos_x": 0.3}, [("QP = 0.2, 0, 0.1", "QP = 0.3, 0, 0.1")]),
    ({"Reference_Marker/22/pos_z": 0.5}, [("QP = 0, 0, 0.3, RM", "QP = 0, 0, 0.5, RM")]),
    ({"Reference_Marker/20/pos_y": -0.2}, [("QP = 0.1, 0, 0\n", "QP = 0.1, -0.2, 0\n")]),
    ({"Reference_Marker/2/pos_z": 2.0}, [("QP = 0, 0, 1,", "QP = 0, 0, 2,")]),
    ({"Body_Rigid/2/w_ic_y": 0.7}, [("WX = 1, WZ = 2", "WX = 1, WY = 0.7, WZ = 2")]),
    ({"Body_Rigid/2/v_ic_y": 0.7}, [("VX = 0.5,", "VX = 0.5, VY = 0.7,")]),
    ({"Reference_Marker/21/pos_x": 0.3, "Reference_Marker/22/pos_z": 0.5,
      "Reference_Marker/23/pos_x": 0.0},
     [("QP = 0.2, 0, 0.1", "QP = 0.3, 0, 0.1"), ("QP = 0, 0, 0.3, RM", "QP = 0, 0, 0.5, RM"),
      ("QP = 0.1, 0.1, 0.3", "QP = 0.0, 0.1, 0.3")]),
]


def test_an_adams_case_means_qp_in_its_parts_frame():
    """In a dataset the paths are QP in the part's frame (RM's when given: the markers placed
    in a marker's frame move with it), VX.. along VM's axes and WX.. along the CM marker's:
    each case, one path or several along an RM chain, runs as the dataset edited by hand, bit
    for bit."""
    model = pysolver.loads(TURNED_PART, fmt="adm", file="turned.adm", simulate=SHORT)
    params = model.compile().parameters
    assert [params._get(f"Reference_Marker/21/pos_{c}") for c in "xyz"] == [0.2, 0.0, 0.1]
    assert params._get("Body_Rigid/2/v_ic_x") == 0.5
    assert model.markers[21].pos[0] != 0.2          # the global place is elsewhere
    for case, edits in TURNED_EDITS:
        text = TURNED_PART
        for old, new in edits:
            assert text.count(old) == 1, old
            text = text.replace(old, new)
        by_hand = pysolver.loads(text, fmt="adm", file="turned.adm", simulate=SHORT)
        _same_run(model.run(progress=False, params=case), by_hand.run(progress=False))
    _same_run(model.run(progress=False), pysolver.loads(
        TURNED_PART, fmt="adm", file="turned.adm", simulate=SHORT).run(progress=False))


def test_the_offset_part_of_the_report():
    """Trial 44's repro: a part at x = 1 whose marker 21 is at QP 0.2: the path reads 0.2, and
    pos_x = 0.5 puts the marker at x = 1.5, as QP = 0.5 does."""
    adm = ("offset part\nPART/1, GROUND\nMARKER/1, PART = 1\n"
           "PART/2, MASS = 1.0, CM = 20, IP = 1, 1, 1, QG = 1, 0, 0\n"
           "MARKER/20, PART = 2, QP = 0, 0, 0\nMARKER/21, PART = 2, QP = 0.2, 0, 0\n"
           "SFORCE/1, TRANSLATION, I = 21, J = 1, FUNCTION = -10*(DM(21,1)-1)\n"
           "REQUEST/1, F1 = DX(20)\\, F2 = DX(21)\nEND\n")
    model = pysolver.loads(adm, fmt="adm", file="off.adm", simulate=SHORT)
    assert model.compile().parameters._get("Reference_Marker/21/pos_x") == 0.2
    res = model.run(progress=False, params={"Reference_Marker/21/pos_x": 0.5})
    assert res.request(1)[0, 1] == 1.5


XML_CROSS = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="20" body_id="2" pos_x="1" yaw="0.4"/>
  <Reference_Marker id="21" body_id="2" pos_x="0.5" pos_y="0.2" rm_id="20"/>
  <Reference_Marker id="30" body_id="3" pos_y="1" rm_id="21" roll="0.3"/>
  <Reference_Marker id="31" body_id="3" pos_z="0.5" rm_id="30"/>
  <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"
              v_ic_x="0.3" vm_id="20" w_ic_z="0.5"/>
  <Body_Point id="3" cg_id="30" mass="0.5"/>
  <Force_SpringDamper id="1" type="TRANSLATIONAL" i_marker_id="31" j_marker_id="1"
      stiffness="2" length="0.5"/>
  <Force_SpringDamper id="2" type="TRANSLATIONAL" i_marker_id="21" j_marker_id="1"
      stiffness="3" length="0.8"/>
  <Post_Request id="1" expr1="DX(21)" expr2="DY(30)" expr3="DZ(31)" expr4="VX(20)"/>
  <Param_Transient integr_tol="1e-8"/>
</Model></MotionSolve>"""


@pytest.mark.parametrize("case, old, new", [
    ({"Reference_Marker/20/pos_x": 2.0}, 'pos_x="1"', 'pos_x="2.0"'),
    ({"Reference_Marker/21/pos_y": -0.4}, 'pos_y="0.2"', 'pos_y="-0.4"'),
    ({"Reference_Marker/30/pos_y": 3.0}, 'pos_y="1" rm_id', 'pos_y="3.0" rm_id'),
    ({"Body_Rigid/2/v_ic_y": 0.25}, 'v_ic_x="0.3"', 'v_ic_x="0.3" v_ic_y="0.25"'),
    ({"Body_Rigid/2/w_ic_x": 0.1}, 'w_ic_z="0.5"', 'w_ic_z="0.5" w_ic_x="0.1"'),
])
def test_an_xml_case_means_pos_in_rm_ids_frame(case, old, new):
    """XML markers with rm_id, across bodies (the point body's cg 30 is placed in body 2's
    marker 21's frame): moving a marker moves those placed in its frame, as the deck does;
    v_ic_* along vm_id's axes, w_ic_* about the global axes (no wm_id)."""
    model = pysolver.loads(XML_CROSS, simulate=SHORT)
    assert XML_CROSS.count(old) == 1
    by_hand = pysolver.loads(XML_CROSS.replace(old, new), simulate=SHORT)
    _same_run(model.run(progress=False, params=case), by_hand.run(progress=False))


def test_a_sweep_of_the_tip_is_the_deck_edited(tmp_path):
    """pysolver.sweep over the tip's place of decks/spinning_top.xml: each row's output is the
    hand-edited deck's."""
    text = (ROOT / "decks/spinning_top.xml").read_text()
    model = pysolver.loads(text, file=str(ROOT / "decks/spinning_top.xml"), simulate=SHORT)
    values = [-0.1, -0.08, -0.05]
    sw = pysolver.sweep(model, [{"Reference_Marker/21/pos_z": v} for v in values],
                        processes=0, outputs={"z": "final:request/1/3"})
    for row, v in zip(sw.rows, values):
        by_hand = pysolver.loads(text.replace('pos_z="-0.1" rm_id', f'pos_z="{v}" rm_id'),
                                 simulate=SHORT).run(progress=False)
        assert row["status"] == "ok" and row["z"] == by_hand.request(1)[-1, 2]
