"""Force_Field and Force_Beam (Adams FIELD and BEAM): the cantilever against Timoshenko's and
Euler-Bernoulli's closed forms, axial and torsion stiffness; a field that is a bushing, a
field with the beam's stiffness that is the beam; a field's force and torque by hand at a
known pose; Newton's third law (the reaction with the moment of its offset, and the momentum
of two free bodies); energy kept without damping and lost with it; the statement forms,
datasets and conversions; bad input; the diagnosis of a non-finite value."""
import re
import warnings

import numpy as np
import pytest

import pysolver
from pysolver import DeckError, DeckWarning
from pysolver.convert import convert

from helpers import DECKS, TEST_DECKS

CANTILEVER = DECKS / "beam_cantilever.xml"
DECK = (TEST_DECKS / "field_beam.xml").read_text()
# the cantilever's numbers (decks/beam_cantilever.xml)
L, E, G, A, IXX, IYY, IZZ, AS = 0.2, 2.1e11, 8.1e10, 1.6e-3, 3.6e-7, 2.1333e-7, 2.1333e-7, 1.2
FX, FY, FZ, TX = 5000.0, 1000.0, -2000.0, 50.0


#: A short transient, for the checks that need a few rows.
SHORT = {"analysis_type": "TRANSIENT", "end_time": 0.2, "print_interval": 0.01}


def _element(text, tag, eid):
    """The text of element `tag` with id `eid` in a deck."""
    start = text.index(f'<{tag} id="{eid}"')
    return text[start:text.index("/>", start) + 2]


def _matrix(element, prefix):
    """The 6x6 matrix `prefix` (k, c) of an element's text, zero where not given."""
    m = np.zeros((6, 6))
    for r, c, v in re.findall(rf'\b{prefix}(\d)(\d)="([^"]+)"', element):
        m[int(r) - 1, int(c) - 1] = float(v)
    return m


def _rot313(psi, theta, phi):
    def rz(a):
        return np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    rx = np.array([[1, 0, 0], [0, np.cos(theta), -np.sin(theta)],
                   [0, np.sin(theta), np.cos(theta)]])
    return rz(psi) @ rx @ rz(phi)


def beam_stiffness(length, e, g, area, ixx, iyy, izz, asy, asz):
    """The beam's 6x6 stiffness by hand (docs/deck-language.md, "Fields and beams")."""
    py = 12 * e * izz * asy / (g * area * length ** 2)
    pz = 12 * e * iyy * asz / (g * area * length ** 2)
    k = np.zeros((6, 6))
    k[0, 0] = e * area / length
    k[3, 3] = g * ixx / length
    k[1, 1] = 12 * e * izz / (length ** 3 * (1 + py))
    k[1, 5] = k[5, 1] = -6 * e * izz / (length ** 2 * (1 + py))
    k[5, 5] = (4 + py) * e * izz / (length * (1 + py))
    k[2, 2] = 12 * e * iyy / (length ** 3 * (1 + pz))
    k[2, 4] = k[4, 2] = 6 * e * iyy / (length ** 2 * (1 + pz))
    k[4, 4] = (4 + pz) * e * iyy / (length * (1 + pz))
    return k


# the cantilever -----------------------------------------------------------------------------
def _deflections(asy, asz, e=E):
    """DX - L, DY, DZ, AX, AY, AZ of the loaded end (Timoshenko; asy = asz = 0: Euler-Bernoulli)."""
    return np.array([FX * L / (e * A),
                     FY * L ** 3 / (3 * e * IZZ) + FY * L * asy / (G * A),
                     FZ * L ** 3 / (3 * e * IYY) + FZ * L * asz / (G * A),
                     TX * L / (G * IXX),
                     -FZ * L ** 2 / (2 * e * IYY),
                     FY * L ** 2 / (2 * e * IZZ)])


def test_a_cantilever_deflects_as_the_timoshenko_closed_form():
    """decks/beam_cantilever.xml's static end: stretch F L / (E A), bending P L^3 / (3 E I) plus
    the shear P L ASY / (G A), its slope P L^2 / (2 E I), twist T L / (G Ixx); the clamp takes
    the load and its moment (BEAM(1, 1, ..)); the transient after it stays there."""
    res = pysolver.load(CANTILEVER).run()
    assert res.success, res.message
    q = res.request(1)
    np.testing.assert_allclose(q[0, :6], _deflections(AS, AS), rtol=1e-9, atol=0)
    dx, dy = L + q[0, 0], q[0, 1]
    np.testing.assert_allclose(q[0, 6], FY, rtol=1e-12)                # the clamp's force
    np.testing.assert_allclose(q[0, 7], dx * FY - dy * FX, rtol=1e-9)   # its moment (z)
    np.testing.assert_allclose(q[-1], q[0], rtol=0, atol=1e-11)
    # the shear's share of the bending is 3 E I ASY / (G A L^2), 3.1 %: visible
    assert 0.03 < (FY * L * AS / (G * A)) / q[0, 1] < 0.035


def test_without_shear_factors_it_is_euler_bernoulli_and_the_numbers_are_parameters():
    """ASY = ASZ = 0 (a sweep case) leaves the Euler-Bernoulli cantilever, P L^3 / (3 E I);
    a case's E changes stretch and bending; the deck's values come back after it."""
    model = pysolver.load(CANTILEVER)
    paths = model.compile().parameters.paths()
    assert {f"Force_Beam/1/{k}" for k in ("length", "e", "g", "area", "ixx", "iyy", "izz",
                                          "asy", "asz", "cratio")} <= set(paths)
    bernoulli = model.run(params={"Force_Beam/1/asy": 0.0, "Force_Beam/1/asz": 0.0})
    np.testing.assert_allclose(bernoulli.request(1)[0, :6], _deflections(0.0, 0.0), rtol=1e-9)
    softer = model.run(params={"Force_Beam/1/e": E / 2})
    np.testing.assert_allclose(softer.request(1)[0, :6], _deflections(AS, AS, E / 2),
                               rtol=1e-9)
    np.testing.assert_allclose(model.run().request(1)[0, :6], _deflections(AS, AS),
                               rtol=1e-9)


def test_a_fields_nonzero_numbers_are_sweep_parameters():
    """field_beam.xml's field 3: its nonzero k entries and cratio are paths, a zero entry is a
    DeckError that says why; a case's stiffness is the deck's with that number."""
    model = pysolver.load(TEST_DECKS / "field_beam.xml", simulate=SHORT)
    paths = set(model.compile().parameters.paths())
    assert {p for p in paths if p.startswith("Force_Field/3/")} == {
        "Force_Field/3/k11", "Force_Field/3/k12", "Force_Field/3/k21", "Force_Field/3/k22",
        "Force_Field/3/k33", "Force_Field/3/cratio"}
    with pytest.raises(DeckError, match="the deck's k13 is 0, so the compiled model has no "
                                        "term of it to change"):
        model.run(params={"Force_Field/3/k13": 5.0})
    swept = model.run(params={"Force_Field/3/k33": 1400.0}).request(2)
    text = (TEST_DECKS / "field_beam.xml").read_text().replace('k33="700"', 'k33="1400"')
    edited = pysolver.loads(text, simulate=SHORT).run().request(2)
    np.testing.assert_array_equal(swept, edited)


# fields against bushings and beams ------------------------------------------------------------
def test_a_diagonal_field_is_the_bushing_of_the_same_numbers():
    """tests/decks/bushing.xml's tumbling body on its bushing and on a field of the same
    diagonal stiffness, damping and preloads: the same motion at every row, to the bit."""
    text = (TEST_DECKS / "bushing.xml").read_text()
    bushing = _element(text, "Force_Bushing", 1)
    nums = dict(re.findall(r'(\w+)="([^"]+)"', bushing))
    comps = ("x", "y", "z", "tx", "ty", "tz")
    diag = [f'k{n}{n}="{nums["k" + c if n < 4 else "kt" + c[1]]}" '
            f'c{n}{n}="{nums["c" + c if n < 4 else "ct" + c[1]]}" '
            f'preload_{c}="{nums["preload_" + c]}"' for n, c in enumerate(comps, 1)]
    field = f'<Force_Field id="1" i_marker_id="21" j_marker_id="5" {" ".join(diag)}/>'
    a = pysolver.loads(text).run()
    b = pysolver.loads(text.replace(bushing, field)).run()
    assert a.success and b.success, (a.message, b.message)
    assert np.abs(a.request(1)[:, :6]).max() > 1e-3
    np.testing.assert_array_equal(a.request(1), b.request(1))


def test_a_field_of_the_beams_stiffness_is_the_beam():
    """field_beam.xml's beam and a field with its stiffness worked out by hand, its length
    along x, its CRATIO and preloads: the same residual and iteration matrix to rounding at
    random states, and the same motion to the integration's tolerance."""
    beam = _element(DECK, "Force_Beam", 2)
    k = beam_stiffness(0.5, 2e8, 8e7, 1e-3, 2e-7, 1e-7, 1.5e-7, 1.2, 1.1)
    entries = " ".join(f'k{r + 1}{c + 1}="{float(k[r, c])!r}"' for r in range(6) for c in range(6)
                       if k[r, c])
    field = (f'<Force_Field id="2" i_marker_id="31" j_marker_id="22" {entries} '
             'length_x="0.5" cratio="0.01" preload_y="0.5" preload_tz="0.02"/>')
    models = [pysolver.loads(DECK), pysolver.loads(DECK.replace(beam, field)
                                                   .replace("BEAM(2", "FIELD(2"))]
    ka, kb = (m.compile().kernel for m in models)
    rng = np.random.default_rng(5)
    y0 = ka.layout.initial_state()
    for _ in range(4):
        y, yp = y0 + 0.02 * rng.normal(size=ka.ny), rng.normal(size=ka.ny)
        ra, rb = ka.residual_array(0.3, y, yp), kb.residual_array(0.3, y, yp)
        np.testing.assert_allclose(rb, ra, rtol=0, atol=1e-11 * np.abs(ra).max())
        ja, jb = ka.jacobian_array(0.3, y, yp, 10.0), kb.jacobian_array(0.3, y, yp, 10.0)
        np.testing.assert_allclose(jb, ja, rtol=0, atol=1e-11 * np.abs(ja).max())
    a, b = (m.run() for m in models)
    assert a.success and b.success, (a.message, b.message)
    for rid in (1, 2):
        np.testing.assert_allclose(b.request(rid), a.request(rid), rtol=0,
                                   atol=1e-5 * np.abs(a.request(rid)).max())


# the law by hand -----------------------------------------------------------------------------
def test_a_fields_force_and_torque_at_a_known_pose_are_the_law_by_hand():
    """Field 1 of field_beam.xml (every entry of K and C) with its I marker moved and turned
    from J: at t = 0 the six deflections (J's axes, AX..AZ by their single-axis formulas), the
    rates (the body's velocity and spin) and FIELD(1, jflag, comp, 5) are the law
    F = -K (X - length) - C V + preload worked out with NumPy; on J at J: -F and -T - d x F."""
    moved = DECK.replace('<Reference_Marker id="21" body_id="2" pos_x="0.1" pos_y="-0.05" '
                         'pos_z="0.02" psi="0.3"\n                      theta="0.2" phi="-0.1"/>',
                         '<Reference_Marker id="21" body_id="2" pos_x="0.11" pos_y="-0.07" '
                         'pos_z="0.035" psi="0.35" theta="0.17" phi="-0.06"/>')
    assert moved != DECK
    reqs = ('<Post_Request id="7" ' + " ".join(f'expr{n + 1}="FIELD(1,0,{c},5)"' for n, c in
                                               enumerate((2, 3, 4, 6, 7, 8))) + "/>"
            '<Post_Request id="8" ' + " ".join(f'expr{n + 1}="FIELD(1,1,{c},5)"' for n, c in
                                               enumerate((2, 3, 4, 6, 7, 8))) + "/>"
            '<Post_Request id="9" expr1="VX(21,5,5,5)" expr2="VY(21,5,5,5)" '
            'expr3="VZ(21,5,5,5)" expr4="WX(21,5,5)" expr5="WY(21,5,5)" expr6="WZ(21,5,5)"/>')
    res = pysolver.loads(moved.replace("</Model>", reqs + "</Model>"), simulate=SHORT).run()
    assert res.success, res.message
    field = _element(DECK, "Force_Field", 1)
    K, C = _matrix(field, "k"), _matrix(field, "c")
    num = dict(re.findall(r'(\w+)="([^"]+)"', field))
    length = np.array([float(num[f"length_{c}"]) for c in ("x", "y", "z", "tx", "ty", "tz")])
    preload = np.array([float(num[f"preload_{c}"]) for c in ("x", "y", "z", "tx", "ty", "tz")])
    # the pose by hand: J on ground, I on body 2 (its axes global, at rest at its cm)
    rj, ri = _rot313(0.3, 0.2, -0.1), _rot313(0.35, 0.17, -0.06)
    oj, oi = np.array([0.1, -0.05, 0.02]), np.array([0.11, -0.07, 0.035])
    v_cm, w = np.array([0.05, -0.1, 0.0]), np.array([0.3, -0.2, 0.5])
    d = rj.T @ (oi - oj)
    xi, yi, zi = ri.T
    xj, yj, zj = rj.T
    angles = [np.arctan2(-zi @ yj, zi @ zj), np.arctan2(zi @ xj, zi @ zj),
              np.arctan2(xi @ yj, xi @ xj)]
    X = np.r_[d, angles]
    V = np.r_[rj.T @ (v_cm + np.cross(w, oi)), rj.T @ w]
    np.testing.assert_allclose(res.request(1)[0, :6], X, rtol=0, atol=1e-14)
    np.testing.assert_allclose(res.request(9)[0, :6], V, rtol=0, atol=1e-14)
    law = -K @ (X - length) - C @ V + preload
    assert np.abs(X - length).min() > 1e-3 and np.abs(law).min() > 1e-2
    np.testing.assert_allclose(res.request(7)[0, :6], law, rtol=1e-12, atol=1e-12)
    on_j = np.r_[-law[:3], -law[3:] - np.cross(d, law[:3])]
    np.testing.assert_allclose(res.request(8)[0, :6], on_j, rtol=1e-12, atol=1e-12)


# Newton's third law -----------------------------------------------------------------------------
def test_action_and_reaction_balance_with_the_moment_of_their_offset():
    """Over field_beam.xml's run, for the field from ground, the beam between two moving bodies
    and the field of the point mass: the force on J is minus the one on I, and the torques on
    I and J with the moment of I's force about J add to zero; an ELEMENTAL_FORCE request of
    elem_type FIELD or BEAM is the element's force function."""
    reqs = []
    for rid, (fn, eid, i, j) in enumerate((("FIELD", 1, 21, 5), ("BEAM", 2, 31, 22),
                                           ("FIELD", 3, 40, 32))):
        for jflag in (0, 1):
            reqs.append(f'<Post_Request id="{10 + 2 * rid + jflag}" ' + " ".join(
                f'expr{n + 1}="{fn}({eid},{jflag},{c},0)"' for n, c in
                enumerate((2, 3, 4, 6, 7, 8))) + f' expr7="DX({i},{j})" expr8="DY({i},{j})"/>')
        reqs.append(f'<Post_Request id="{20 + rid}" expr1="DZ({i},{j})"/>')
    reqs.append('<Post_Request id="30" type="ELEMENTAL_FORCE" elem_type="Force_Beam" '
                'elem_id="2" jflag="1"/>')
    res = pysolver.loads(DECK.replace("</Model>", "".join(reqs) + "</Model>")).run()
    assert res.success, res.message
    for rid in range(3):
        on_i, on_j = res.request(10 + 2 * rid), res.request(11 + 2 * rid)
        d = np.c_[on_i[:, 6:8], res.request(20 + rid)[:, 0]]
        scale = np.abs(on_i[:, :6]).max()
        assert scale > 0.1
        np.testing.assert_allclose(on_i[:, :3] + on_j[:, :3], 0, atol=1e-12 * scale)
        np.testing.assert_allclose(on_i[:, 3:6] + on_j[:, 3:6] + np.cross(d, on_i[:, :3]), 0,
                                   atol=1e-12 * scale)
    beam_on_j = res.request(13)
    np.testing.assert_array_equal(res.request(30)[:, [1, 2, 3, 5, 6, 7]], beam_on_j[:, :6])


FREE = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="20" body_id="2" pos_x="0.2" pos_y="0.1"/>
  <Reference_Marker id="21" body_id="2" pos_x="0.5" pos_y="0.12" pos_z="0.01" psi="0.2"/>
  <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="0.05" inertia_yy="0.05" inertia_zz="0.05"
              v_ic_x="0.3" v_ic_y="-0.2" w_ic_x="1" w_ic_z="-2"/>
  <Reference_Marker id="30" body_id="3" pos_x="0.9" pos_y="-0.1" pos_z="0.05"/>
  <Reference_Marker id="31" body_id="3" pos_x="0.52" pos_y="0.1" psi="0.1" theta="0.05"/>
  <Body_Rigid id="3" cg_id="30" mass="1.5" inertia_xx="0.03" inertia_yy="0.03"
              inertia_zz="0.03" v_ic_z="0.4" w_ic_y="3"/>
  {field}
  {requests}
  <Param_Transient integr_tol="1e-10"/>
</Model><Simulate analysis_type="Transient" end_time="1" print_interval="0.01"/></MotionSolve>"""


def _free(field):
    """Two free bodies (isotropic inertia) joined by `field` alone: their positions,
    velocities and spins, global, by body."""
    reqs = "".join(
        f'<Post_Request id="{10 * b + k}" expr1="{f}X({m})" expr2="{f}Y({m})" '
        f'expr3="{f}Z({m})"/>' for b, m in ((2, 20), (3, 30)) for k, f in enumerate("DVW"))
    res = pysolver.loads(FREE.format(field=field, requests=reqs)).run()
    assert res.success, res.message
    return res, {b: [res.request(10 * b + k)[:, :3] for k in range(3)] for b in (2, 3)}


def test_two_free_bodies_on_a_field_keep_their_momentum():
    """Bodies joined only by field 1's law (every entry of K and C, lengths, preloads): the
    total momentum stays what it was (a linear invariant, which the integration keeps to its
    tolerance and the law's equal and opposite forces keep exactly) and so does the angular
    momentum about the origin, which needs the reaction's moment."""
    field = _element(DECK, "Force_Field", 1).replace('i_marker_id="21" j_marker_id="5"',
                                                     'i_marker_id="31" j_marker_id="21"')
    res, s = _free(field)
    mass, inertia = {2: 2.0, 3: 1.5}, {2: 0.05, 3: 0.03}
    p = sum(mass[b] * s[b][1] for b in (2, 3))
    h = sum(mass[b] * np.cross(s[b][0], s[b][1]) + inertia[b] * s[b][2] for b in (2, 3))
    assert np.abs(s[2][2] - s[2][2][0]).max() > 0.1          # the field turns the bodies
    np.testing.assert_allclose(p, np.broadcast_to(p[0], p.shape), rtol=0, atol=1e-9)
    np.testing.assert_allclose(h, np.broadcast_to(h[0], h.shape), rtol=0,
                               atol=1e-7 * np.abs(h[0]).max())


# energy -----------------------------------------------------------------------------------------
PLANAR = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="5" body_id="1" psi="0.4"/>
  <Reference_Marker id="20" body_id="2" pos_x="0.6" pos_y="0.3"/>
  <Reference_Marker id="21" body_id="2" pos_x="0.5" pos_y="0.2" psi="0.5"/>
  <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="0.05" inertia_yy="0.06" inertia_zz="0.07"
              v_ic_x="0.4" v_ic_y="-0.3" w_ic_z="1.5"/>
  <Force_Field id="1" i_marker_id="21" j_marker_id="5" k11="800" k12="-150" k16="20"
               k21="-150" k22="600" k26="-45" k61="20" k62="-45" k66="9" k33="500" k44="10"
               k55="12" length_x="0.45" length_y="0.1" length_tz="0.05" {damping}/>
  <Post_Request id="1" expr1="DX(21,5,5)" expr2="DY(21,5,5)" expr3="AZ(21,5)" expr4="KE(2)"
                expr5="DZ(21,5,5)" expr6="AX(21,5)" expr7="AY(21,5)"/>
  <Param_Transient integr_tol="1e-10"/>
</Model><Simulate analysis_type="Transient" end_time="2" print_interval="0.005"/></MotionSolve>"""


def _energy(damping):
    res = pysolver.loads(PLANAR.format(damping=damping)).run()
    assert res.success, res.message
    q = res.request(1)
    np.testing.assert_allclose(q[:, 4:7], 0, atol=1e-12)     # it stays in its plane
    K = np.array([[800, -150, 20], [-150, 600, -45], [20, -45, 9]])
    x = q[:, :3] - [0.45, 0.1, 0.05]
    return q[:, 3] + 0.5 * np.einsum("ti,ij,tj->t", x, K, x)


def test_without_damping_a_field_keeps_its_energy_and_with_it_loses_energy():
    """A body on a field from ground moving in the x-y plane (stiffness coupling x, y and the
    angle about z; in the plane AZ is the angle itself, so the law is the gradient of
    V = (X - length)' K (X - length) / 2): kinetic energy plus V stays what it was to the
    integration's tolerance; with CRATIO it only falls, and falls far."""
    kept = _energy("")
    assert kept[0] > 1.0
    np.testing.assert_allclose(kept, kept[0], rtol=2e-7)
    lost = _energy('cratio="0.02"')
    assert lost[0] == kept[0]
    assert np.all(np.diff(lost) <= 1e-12 * lost[0])
    assert lost[-1] < 0.2 * lost[0]


# the statement forms ------------------------------------------------------------------------------
ADM = """field and beam, as FAST's datasets write them
PART/1, GROUND
MARKER/1, PART = 1
MARKER/5, PART = 1, QP = 0.1, -0.05, 0.02, REULER = 0.3, 0.2, -0.1
PART/2, MASS = 2, CM = 20, IP = 0.02, 0.03, 0.04
MARKER/20, PART = 2
MARKER/21, PART = 2, QP = 0.1, -0.05, 0.02, REULER = 0.3, 0.2, -0.1
MARKER/22, PART = 2, QP = 0.3, 0, 0
PART/3, MASS = 1, CM = 30, IP = 0.01, 0.02, 0.02
MARKER/30, PART = 3, QP = 0.8, 0, 0
MARKER/31, PART = 3, QP = 0.8, 0.01, 0, REULER = 0.01D, 0, 0
FIELD/1
, I = 21
, J = 5
, CMATRIX =
,  24, -10, 1.4, 0.25, -0.24, -0.18
, -10, 34, 1, 0.6, -0.49, 0.56
,  1.3, 0.96, 9.7, -0.057, -0.52, -0.26
,  0.18, 0.63, -0.12, 0.026, 0.015, -0.028
, -0.15, -0.42, -0.44, 0.011, 0.092, 0.056
, -0.18, 0.54, -0.12, 0.022, -0.0061, 0.13
, KMATRIX =
,  12300, -5220, 673, 131, -80.8, -109
, -5220, 17000, 477, 318, -246, 253
,  673, 477, 4870, -34.4, -234, -74.7
,  131, 318, -34.4, 75.1, -11.6, -1.45
, -80.8, -246, -234, -11.6, 96.9, 19.8
, -109, 253, -74.7, -1.45, 19.8, 82
, LENGTH = 0.02, -0.01, 0.005, 0.01, -0.02, 0.015
, FORCE = 1, -2, 0.5, 0.1, -0.05, 0.02
BEAM/2, I = 31, J = 22, LENGTH = 0.5, IXX = 2e-7, IYY = 1e-7, IZZ = 1.5e-7, AREA = 1e-3
, ASY = 1.2, ASZ = 1.1, EMODULUS = 2e8, GMODULUS = 8e7
, CMATRIX = 1, 0, 0, 0, 0, 0.1, 2, 0, 0, 0.2, 0, 3, 0.3, 0, 0, 0.04, 0, 0, 0.05, 0, 0.06
, FORCE = 0, 0.5, 0, TORQUE = 0, 0, 0.02
REQUEST/1, F1 = DX(21,5,5)\\, F2 = AZ(21,5)\\, F3 = FIELD(1,0,3,5)\\, F4 = BEAM(2,1,8,0)\\
END
"""
XML = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="5" body_id="1" pos_x="0.1" pos_y="-0.05" pos_z="0.02" psi="0.3"
                    theta="0.2" phi="-0.1"/>
  <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="0.02" inertia_yy="0.03"
              inertia_zz="0.04"/>
  <Reference_Marker id="20" body_id="2"/>
  <Reference_Marker id="21" body_id="2" pos_x="0.1" pos_y="-0.05" pos_z="0.02" psi="0.3"
                    theta="0.2" phi="-0.1"/>
  <Reference_Marker id="22" body_id="2" pos_x="0.3"/>
  <Body_Rigid id="3" cg_id="30" mass="1" inertia_xx="0.01" inertia_yy="0.02"
              inertia_zz="0.02"/>
  <Reference_Marker id="30" body_id="3" pos_x="0.8"/>
  <Reference_Marker id="31" body_id="3" pos_x="0.8" pos_y="0.01" psi="{psi!r}"/>
  {field}
  <Force_Beam id="2" i_marker_id="31" j_marker_id="22" length="0.5" E="2e8" G="8e7"
              area="1e-3" ixx="2e-7" iyy="1e-7" izz="1.5e-7" ASY="1.2" ASZ="1.1" c11="1"
              c16="0.1" c61="0.1" c22="2" c25="0.2" c52="0.2" c33="3" c34="0.3" c43="0.3"
              c44="0.04" c55="0.05" c66="0.06" preload_y="0.5" preload_tz="0.02"/>
  <Post_Request id="1" expr1="DX(21,5,5)" expr2="AZ(21,5)" expr3="FIELD(1,0,3,5)"
                expr4="BEAM(2,1,8,0)"/>
</Model></MotionSolve>"""


def _xml():
    field = _element(DECK, "Force_Field", 1)
    return XML.format(field=field, psi=float(np.radians(0.01)))


def _same(a, b):
    """Two models hold the same fields, beams and laws, number for number."""
    assert a.fields == b.fields and a.beams == b.beams
    assert list(a.vforces) == list(b.vforces)
    for key, law in a.vforces.items():
        assert (law.i, law.j, law.ref, law.owner, law.exprs) == \
            (b.vforces[key].i, b.vforces[key].j, b.vforces[key].ref, b.vforces[key].owner,
             b.vforces[key].exprs)


def test_a_dataset_in_adams_order_builds_the_xml_model(tmp_path):
    """FIELD's KMATRIX and CMATRIX column by column (each list starting on the line after its
    keyword, as FAST's datasets write them; the transposed CMATRIX here is read as the XML's
    rows), LENGTH with an angle in degrees; BEAM's CMATRIX as Adams' 21 numbers of the lower
    half column by column, its preloads as FORCE and TORQUE: the XML's model, number for
    number, and the same motion."""
    adm = tmp_path / "fast_like.adm"
    adm.write_text(ADM.replace("\n", "\r\n"))
    a, b = pysolver.load(adm, simulate=SHORT), pysolver.loads(_xml(), simulate=SHORT)
    _same(a, b)
    ra, rb = a.run(), b.run()
    assert ra.success and rb.success
    np.testing.assert_array_equal(ra.request(1), rb.request(1))


def test_every_form_converts_and_builds_the_same_model(tmp_path):
    """tests/decks/field_beam.xml to a dataset, a statement script (via the dataset's
    msolve classes) and back to XML, and each converted again: the same fields, beams and
    laws and the same motion."""
    ref = pysolver.load(TEST_DECKS / "field_beam.xml", simulate=SHORT)
    run = ref.run()
    for ext in (".adm", ".py", ".xml"):
        first = tmp_path / f"first{ext}"
        convert(TEST_DECKS / "field_beam.xml", first)
        again = tmp_path / f"again{ext}.xml"
        convert(first, again)
        for path in (first, again):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", DeckWarning)
                model = pysolver.load(path, simulate=SHORT)
            _same(ref, model)
            res = model.run()
            for rid in (1, 2):
                np.testing.assert_array_equal(res.request(rid), run.request(rid))
    text = (tmp_path / "first.adm").read_text()
    assert "FIELD/1, I = 21, J = 5" in text and "BEAM/2, I = 31, J = 22" in text
    assert ", CMATRIX = 24.0, -10.0, 1.4, 0.25, -0.24, -0.18, -10.0" in text
    # XML with MotionSolve's spelling of Force_Field's and Force_Beam's attributes
    xml = (tmp_path / "again.adm.xml").read_text()
    assert 'K11="12300.0" K12="-5220.0"' in xml and 'C66="0.13"' in xml
    assert 'E="200000000.0" G="80000000.0"' in xml and 'ASY="1.2" ASZ="1.1"' in xml


def test_the_python_statements_take_matrices_by_rows_or_columns(tmp_path):
    """FIELD(KMATRIX=) as a 6x6 array by rows and as Adams' 36 numbers by columns, BEAM with
    CMATRIX as Adams' 21: the same model as the XML."""
    field = _element(DECK, "Force_Field", 1)
    K, C = _matrix(field, "k"), _matrix(field, "c")
    deck = tmp_path / "fb.py"
    deck.write_text(
        "import numpy as np\nfrom pysolver.msolve import *\n"
        "PART(1, GROUND=True)\nMARKER(1, PART=1)\n"
        "MARKER(5, PART=1, QP=[0.1, -0.05, 0.02], REULER=[0.3, 0.2, -0.1])\n"
        "PART(2, MASS=2, CM=20, IP=[0.02, 0.03, 0.04])\nMARKER(20, PART=2)\n"
        "MARKER(21, PART=2, QP=[0.1, -0.05, 0.02], REULER=[0.3, 0.2, -0.1])\n"
        "MARKER(22, PART=2, QP=[0.3, 0, 0])\n"
        "PART(3, MASS=1, CM=30, IP=[0.01, 0.02, 0.02])\nMARKER(30, PART=3, QP=[0.8, 0, 0])\n"
        f"MARKER(31, PART=3, QP=[0.8, 0.01, 0], REULER=[{np.radians(0.01)!r}, 0, 0])\n"
        f"FIELD(1, I=21, J=5, KMATRIX=np.array({K.tolist()}), "
        f"CMATRIX={C.T.ravel().tolist()}, LENGTH=[0.02, -0.01, 0.005, 0.01, -0.02, 0.015], "
        "FORCE=[1, -2, 0.5, 0.1, -0.05, 0.02])\n"
        "BEAM(2, I=31, J=22, LENGTH=0.5, IXX=2e-7, IYY=1e-7, IZZ=1.5e-7, AREA=1e-3, ASY=1.2, "
        "ASZ=1.1, EMODULUS=2e8, GMODULUS=8e7, CMATRIX=[1, 0, 0, 0, 0, 0.1, 2, 0, 0, 0.2, 0, "
        "3, 0.3, 0, 0, 0.04, 0, 0, 0.05, 0, 0.06], FORCE=[0, 0.5, 0], TORQUE=[0, 0, 0.02])\n"
        "REQUEST(1, F1='DX(21,5,5)', F2='AZ(21,5)', F3='FIELD(1,0,3,5)', "
        "F4='BEAM(2,1,8,0)')\n")
    _same(pysolver.load(deck), pysolver.loads(_xml()))


def test_the_msolve_classes_take_matrices_by_rows(tmp_path):
    """Field(kmatrix=K) with K a 6x6 array by rows and Beam(cmatrix=) likewise: written as
    Adams' columns, read back as the rows given."""
    K = np.diag([100.0, 200, 300, 4, 5, 6])
    K[1, 5], K[5, 1] = -10.0, -12.0
    C = np.arange(36.0).reshape(6, 6)
    deck = tmp_path / "classes.py"
    deck.write_text(
        "import numpy as np\nfrom pysolver.msolve import *\nmodel = Model()\n"
        "ground = Part(ground=True)\nj = Marker(body=ground)\n"
        "b = Part(mass=1, ip=[1, 1, 1])\nb.cm = Marker(body=b, qp=[1, 0, 0])\n"
        "i = Marker(body=b, qp=[1, 0, 0])\n"
        f"Field(i=i, j=j, kmatrix=np.array({K.tolist()}), cratio=0.01, "
        "length=[1, 0, 0, 0, 0, 0])\n"
        "Beam(i=i, j=j, length=1, ixx=1e-6, iyy=1e-6, izz=1e-6, area=1e-4, emodulus=1e9, "
        f"gmodulus=4e8, cmatrix={C.tolist()}, force=[0, 1, 0], torque=[0, 0, 2])\n")
    model = pysolver.load(deck)
    assert model.fields[1].stiffness == tuple(K.ravel())
    assert model.beams[1].damping == tuple(C.ravel())
    assert model.beams[1].preload == (0.0, 1.0, 0.0, 0.0, 0.0, 2.0)


# bad input ----------------------------------------------------------------------------------------
_POINT = '<Reference_Marker id="9" body_id="9" pos_x="5"/><Body_Point id="9" cg_id="9" mass="1"/>'


@pytest.mark.parametrize("element, attribute, words", [
    ('<Force_Field id="9" i_marker_id="40" j_marker_id="32" k11="1" cratio="0.1" c12="2"/>',
     "cratio", r"give cratio \(C = cratio K\) or the damping matrix \(c12...\), not both"),
    ('<Force_Field id="9" i_marker_id="40" j_marker_id="32" usrsub_fnc_name="fiesub"/>',
     "usrsub_fnc_name", "a nonlinear field \\(a FIESUB user subroutine\\) is not supported"),
    ('<Force_Field id="9" i_marker_id="21" j_marker_id="22" k11="1"/>', "j_marker_id",
     "markers 21 and 22 are on one body: a field between them does nothing"),
    ('<Force_Field id="9" i_marker_id="9" j_marker_id="40" k11="1" k15="2"/>', "i_marker_id",
     "a field's rotations needs rigid bodies; marker 9 is on point body 9"),
    ('<Force_Field id="9" i_marker_id="9" j_marker_id="98" k11="1"/>', "j_marker_id",
     "marker 98 does not exist"),
    ('<Force_Beam id="9" i_marker_id="31" j_marker_id="5" length="1" G="1" area="1" ixx="1" '
     'iyy="1" izz="1"/>', "e", "missing required attribute"),
    ('<Force_Beam id="9" i_marker_id="31" j_marker_id="5" length="0" E="1" G="1" area="1" '
     'ixx="1" iyy="1" izz="1"/>', "length", "got 0; expected a value > 0"),
    ('<Force_Beam id="9" i_marker_id="9" j_marker_id="5" length="1" E="1" G="1" area="1" '
     'ixx="1" iyy="1" izz="1"/>', "i_marker_id", "a beam needs rigid bodies"),
])
def test_a_bad_field_or_beam_is_a_deck_error(element, attribute, words):
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(DECK.replace("</Model>", f"{_POINT}{element}</Model>"))
    assert err.value.attribute == attribute


@pytest.mark.parametrize("statement, attribute, words", [
    ("FIELD/9, I = 21, J = 1, KMATRIX = " + ", ".join(["1"] * 35), "KMATRIX",
     "KMATRIX takes 36 numbers, got 35"),
    ("FIELD/9, I = 21, J = 1, FUNCTION = USER(1, 2)", "FUNCTION",
     "FUNCTION is not supported: a nonlinear field"),
    ("BEAM/9, I = 21, J = 1, LENGTH = 1, IXX = 1, IYY = 1, IZZ = 1, AREA = 1, EMOD = 1, "
     "GMOD = 1, FORMULATION = NONLINEAR", "FORMULATION",
     "FORMULATION = NONLINEAR is not supported: pysolver's BEAM is the linear Timoshenko"),
    ("BEAM/9, I = 21, J = 1, LENGTH = 1, IXX = 1, IYY = 1, IZZ = 1, AREA = 1, EMOD = 1, "
     "GMOD = 1, CMATRIX = " + ", ".join(["1"] * 20), "CMATRIX",
     "CMATRIX takes 21 or 36 numbers, got 20"),
])
def test_a_bad_statement_is_a_deck_error(tmp_path, statement, attribute, words):
    deck = tmp_path / "bad.adm"
    deck.write_text("bad\nPART/1, GROUND\nMARKER/1, PART = 1\nPART/2, MASS = 1, CM = 21, "
                    "IP = 1, 1, 1\nMARKER/21, PART = 2, QP = 1, 0, 0\n" + statement + "\nEND\n")
    with pytest.raises(DeckError, match=words) as err:
        pysolver.load(deck)
    assert (err.value.line, err.value.attribute) == (6, attribute)


def test_a_matrix_of_the_wrong_size_in_a_python_deck_is_a_deck_error(tmp_path):
    deck = tmp_path / "bad.py"
    deck.write_text("from pysolver.msolve import *\nPART(1, GROUND=True)\nMARKER(1, PART=1)\n"
                    "FIELD(9, I=1, J=1, KMATRIX=[1, 2, 3])\n")
    with pytest.raises(DeckError, match=r"got \[1, 2, 3\]; expected 36 numbers \(column by "
                                        r"column\) or a 6x6 matrix \(rows\)") as err:
        pysolver.load(deck)
    assert (err.value.line, err.value.attribute) == (4, "KMATRIX")


def test_a_field_and_a_beam_that_go_non_finite_are_named_with_their_laws():
    """The diagnosis names the Force_Field and the Force_Beam by their own ids and quotes
    their laws."""
    from pysolver.build.bindings import lib
    from pysolver.solve import nonfinite
    compiled = pysolver.load(TEST_DECKS / "field_beam.xml").compile()
    kernel = compiled.kernel
    named = {}
    for k, (kind, *_) in enumerate(kernel.elements):
        if kind == "vforce":
            name, rec = nonfinite._element(compiled.model, kernel, lib.PS_BAD_ELEMENT, k)
            named[(name, rec.id)] = "; ".join(rec.texts)
    assert set(named) == {("Force_Field", 1), ("Force_Beam", 2), ("Force_Field", 3)}
    assert named[("Force_Field", 1)].startswith("-k11 (DX(21, 5, 5) - length_x) - k12 (DY(")
    assert "-K22 (DY(31, 22, 22) + cratio VY(31, 22, 22, 22)) - K26 (AZ(31, 22)" in \
        named[("Force_Beam", 2)]
    assert "-k11 (DX(40, 32, 32) + cratio VX(40, 32, 32, 32))" in named[("Force_Field", 3)]
