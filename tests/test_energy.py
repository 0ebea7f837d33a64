"""KE(id): kinetic energy of a body or of every body, against the expression written out, in
the deck's units, following the run's masses and inertias."""
import numpy as np
import pytest

import pysolver
from pysolver import DeckError

from helpers import ROOT

PENDULUM = (ROOT / "decks" / "joints" / "pendulum_revolute.xml").read_text().replace(
    "</Model>", '<Post_Request id="2" expr1="KE(2)" expr2="KE(0)" expr3="KE(1)" '
                'expr4="0.5*(VX(20)**2 + VY(20)**2) + 0.5*1E-3*WZ(20)**2"/></Model>')


def test_the_kinetic_energy_of_the_pendulum_is_half_m_v2_plus_half_i_w2():
    """KE(2) and KE(0) (the only moving body) equal the expression at every row; ground's is
    0; with the mass and inertia changed by params= it follows them (the same rows as the
    edited deck's), and the next run has the deck's again."""
    model = pysolver.loads(PENDULUM)
    q = model.run().request(2)
    assert q[:, 3].max() > 15                              # a swing, not rest
    np.testing.assert_allclose(q[:, 0], q[:, 3], rtol=1e-14, atol=1e-12)
    np.testing.assert_allclose(q[:, 1], q[:, 3], rtol=1e-14, atol=1e-12)
    assert np.all(q[:, 2] == 0)
    res = model.run(params={"Body_Rigid/2/mass": 3.0, "Body_Rigid/2/inertia_zz": 2e-3})
    v = res.request(1)
    np.testing.assert_allclose(res.request(2)[:, 0],
                               1.5 * (v[:, 2] ** 2 + v[:, 3] ** 2) + 1e-3 * v[:, 4] ** 2,
                               rtol=1e-14, atol=1e-12)
    np.testing.assert_array_equal(model.run().request(2), q)
    assert not [p for p in model.compile().parameters.paths() if p.startswith("KE/")]


def test_kinetic_energy_is_in_force_times_length_units_and_sums_every_body():
    """A 2 kg point at 1000 mm/s in a kg/mm/s/N deck has 1 J = 1000 N mm; a spinning 0.4
    kg mm^2 disc at 10 rad/s adds 20 kg mm^2/s^2 = 0.02 N mm; KE(0) is their sum."""
    deck = """<MotionSolve><Model>
      <Units mass="KILOGRAM" length="MILLIMETER" time="SECOND" force="NEWTON"/>
      <Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
      <Reference_Marker id="9" body_id="2"/><Body_Point id="2" cg_id="9" mass="2" v_ic_x="1000"/>
      <Reference_Marker id="30" body_id="3" pos_y="50"/>
      <Body_Rigid id="3" cg_id="30" mass="1" inertia_xx="0.3" inertia_yy="0.3" inertia_zz="0.4"
        w_ic_z="10"/>
      <Post_Request id="1" expr1="KE(2)" expr2="KE(3)" expr3="KE(0)"/></Model>
      <Simulate analysis_type="Transient" end_time="0.1" print_interval="0.1"/></MotionSolve>"""
    np.testing.assert_allclose(pysolver.loads(deck).run().request(1)[:, :3],
                               [[1000.0, 0.02, 1000.02]] * 2, rtol=1e-12)


def test_an_unknown_body_is_a_deck_error():
    with pytest.raises(DeckError, match="body id 7, which does not exist"):
        pysolver.loads(PENDULUM.replace('expr3="KE(1)"', 'expr3="KE(7)"'))
