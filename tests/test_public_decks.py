"""What real public decks written by others use and pysolver now reads (trial 44): Adams/View's
KINEMATICS and IC statements (settings only), FUNCTION = USER(...) without ROUTINE worded in
Adams' terms, Altair Inspire's msolve header (Model(label=), H3dOutput, Output's and the
settings classes' own attributes, External, Pinput, Poutput, simulate(type="STATICS",
dtout=0)), warnings shown at the user's line (one line each from the pysolver command), and
MotionSolve XML elements pysolver does not model named as such. Messages are checked whole;
runs against closed forms."""
import re
import subprocess
import sys
import warnings

import numpy as np
import pytest

import pysolver
from pysolver import DeckError, DeckWarning
from pysolver.deck.schema import SCHEMA
from pysolver.deck.unmodelled import NOT_MODELLED, SET_ASIDE

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]

#: A pendulum as Adams/View writes it (its ANALYSIS SETTINGS block at the end): a 1 kg point
#: 1 m from a revolute about z, gravity -y; {extra} the statement under test.
PENDULUM = """pendulum
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 0.01, 0.01, 0.01
MARKER/20, PART = 2, QP = 1, 0, 0
MARKER/21, PART = 2
JOINT/1, REVOLUTE, I = 21, J = 1
ACCGRAV/JGRAV = -9.80665
INTEGRATOR/GSTIFF, ERROR = 1.0E-04
{extra}
END
"""


def _load(path, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = pysolver.load(str(path), **kw)
    return model, [str(w.message) for w in caught if issubclass(w.category, DeckWarning)]


@pytest.mark.parametrize("extra, warning", [
    ("KINEMATICS/HMAX = 0.01, ERROR = 1.0E-4, ALIMIT = 30D",
     "KINEMATICS: KINEMATICS only sets the tolerances of Adams' kinematic analysis; pysolver "
     "runs SIMULATE/KINEMATICS as a transient, with INTEGRATOR's settings (docs/adams.md, "
     "\"Commands\"); set aside"),
    ("IC/ERROR = 1.0E-10, AERROR = 1.0E-4",
     "IC: IC only sets the tolerances of Adams' initial-conditions analysis; pysolver "
     "assembles the initial conditions to its own tolerances (docs/deck-language.md, "
     "\"Initial positions\"); set aside"),
])
def test_kinematics_and_ic_statements_are_settings_set_aside(tmp_path, extra, warning):
    """Adams/View writes KINEMATICS into every dataset's analysis settings (4 of 7 real
    decks stopped there); IC is the initial-conditions analysis' tolerances. The model is the
    pendulum's without them: released from horizontal, its angular acceleration is g / l."""
    path = tmp_path / "pendulum.adm"
    path.write_text(PENDULUM.format(extra=extra))
    model, caught = _load(path)
    assert caught == [f"{path}:11, {warning}"]
    res = model.run(integr_tol=1e-8)
    assert res.success
    # the cm falls as the pendulum: y(t) of a point pendulum with I = 0.01 about its cm
    alpha = 9.80665 * 1 / (1 + 0.01)
    y = res.y[1, res.state_names.index("body2.y")]
    assert y == pytest.approx(-0.5 * alpha * res.t[1] ** 2, rel=1e-3)


def test_a_settings_statements_keywords_are_checked(tmp_path):
    path = tmp_path / "typo.adm"
    path.write_text(PENDULUM.format(extra="KIN/HMAXX = 0.01"))
    with pytest.raises(DeckError) as err:
        pysolver.load(str(path))
    assert str(err.value) == (
        f"{path}:11, KINEMATICS, attribute 'HMAXX': unknown keyword HMAXX; did you mean HMAX? "
        "(KINEMATICS takes AERROR, ALIMIT, AMAXIT, APATTERN, ERROR, HMAX, MAXIT, PATTERN, "
        "TLIMIT)")


def test_ic_and_statics_without_output_steps_in_a_command_file(tmp_path):
    """An IC command is set aside as the statement; SIMULATE/STATICS, END = 0, DTOUT = 0 (no
    output step, as Inspire writes it) is one equilibrium: the pendulum hangs straight down,
    its cm at (0, -1) (it starts at (1, 0))."""
    (tmp_path / "p.adm").write_text(PENDULUM.format(extra=""))
    acf = tmp_path / "p.acf"
    acf.write_text("p\nout\nIC/ERROR = 1.0E-9\nSIMULATE/STATICS, END = 0, DTOUT = 0\nSTOP\n")
    model, caught = _load(acf)
    assert caught == [
        f"{acf}:3, IC: IC only sets the tolerances of Adams' initial-conditions analysis; "
        "pysolver assembles the initial conditions to its own tolerances "
        "(docs/deck-language.md, \"Initial positions\"); set aside"]
    assert [(c.analysis, c.end_time) for c in model.commands] == [("STATIC", 0.0)]
    res = model.run()
    assert res.success and [s.success for s in res.statics] == [True]
    names = res.state_names
    xy = res.y[-1, [names.index("body2.x"), names.index("body2.y")]]
    np.testing.assert_allclose(xy, [0, -1], atol=1e-6)


def test_user_variable_without_routine_is_worded_in_adams_terms(tmp_path):
    """FAST's datasets give VARIABLE/..., FUNCTION = USER(...) with no ROUTINE: Adams calls
    the VARSUB linked into its user library."""
    path = tmp_path / "var.adm"
    path.write_text(PENDULUM.format(extra="VARIABLE/1, FUNCTION = USER(1)"))
    with pytest.raises(DeckError) as err:
        pysolver.load(str(path))
    assert str(err.value) == (
        f"{path}:11, VARIABLE/1, attribute 'FUNCTION': FUNCTION = USER(...) without ROUTINE "
        "calls Adams' default VARSUB, the one linked into Adams' user library, and pysolver "
        "links no library: give ROUTINE = library::VARSUB (a C library), or SCRIPT = file.py "
        "and ROUTINE = the name of its Python function (docs/adams.md, \"User subroutines\")")


def test_plant_inputs_and_outputs_say_what_they_are(tmp_path):
    path = tmp_path / "plant.adm"
    path.write_text(PENDULUM.format(extra="VARIABLE/1, FUNCTION = DX(20)\n"
                                          "PINPUT/1, VARIABLES = 1\nPOUTPUT/2, VARIABLES = 1"))
    _, caught = _load(path)
    assert caught == [
        f"{path}:12, PINPUT/1: PINPUT only names the variables that are a plant's inputs for "
        "Adams' linearization and control co-simulation; set aside",
        f"{path}:13, POUTPUT/2: POUTPUT only names the variables that are a plant's outputs "
        "for Adams' linearization and control co-simulation; set aside"]


#: The header, one actuator and the commands every Altair Inspire msolve export has (their
#: form, written for this test): a 1 kg block on a translational joint driven along z.
INSPIRE = '''from msolve import *

def createTheModel():
    Model_0 = Model(label='Bench', output='Bench')
    Units(force='NEWTON', length='METER', mass='KILOGRAM', time='SECOND')
    Accgrav(jgrav=-9.80665)
    Integrator(error=0.001, hmax=0.001, dae_jacob_init=1, kmax=5, maxit=4,
               pattern='TFFFT', dae_index=3, dae_constr_tol=1e-07)
    Equilibrium(type='STATIC', skip_mkeam=True, error=0.0001, maxit=50, imbalance=0.0001,
                kinetic_energy_error=1e-05, stability=1e-10)
    Output(req_angle_radians=True, capture_max_pd=True, req_comment_only=True, azero=0.0,
           dzero=0.0, fzero=0.0, vzero=0.0)
    H3dOutput(save=True, linear_anim=False, format_type='MODAL', stress_format='TENSOR',
              strain_format='TENSOR', capture_max_pd=True)
    ground = Part(id=1, label='Ground Body', ground=True)
    gm = Marker(id=10, label='Global Frame', part=ground)
    block = Part(id=2, label='block', mass=1.0, ip=[0.01, 0.01, 0.01])
    block.cm = Marker(id=20, part=block)
    External(id=30, label='block - CADGraphic', color='89:89:89', file='C:/cad/bench.x_t',
             element=['block'], refinement_level=60, rm=block.cm)
    Joint(type='TRANSLATIONAL', i=Marker(id=21, part=block), j=gm)
    Variable(id=40, label='Actuator - Travel', penalty=100.0, penalty1=100.0,
             function='DZ(20, 10, 10)')
    Poutput(id=41, label='Actuator - Plant Outputs', variables=[40])
    Request(id=50, label='Actuator - Output', type='EXPRESSION', f2='DZ(20, 10, 10)',
            f3='VZ(20, 10, 10, 10)', cnames=['', 'Displacement', 'Velocity', '', '', '', '',
                                             ''], results_name='kinematic_output')
    Motion(id=60, label='Actuator Constraint', i=block.cm, j=gm, direction='Z', icdisp=0.0,
           icvel=0.0, function='0.01*TIME')
    return Model_0

model = createTheModel()
model.simulate(type='STATICS', end=0.0, active_contact_iteration=True, dtout=0.0)
model.simulate(type='TRANSIENT', end=1.0, active_contact_iteration=True, dtout=0.25)
'''


def test_an_inspire_export_loads_and_runs(tmp_path):
    """Every line of Inspire's header loads; Pinput/Poutput are set aside with a warning at
    their line, the settings-only attributes are taken quietly, the static command without
    output steps is one equilibrium, and the motion drives the block: DZ = 0.01 t."""
    path = tmp_path / "bench.py"
    path.write_text(INSPIRE)
    model, caught = _load(path)
    assert caught == [
        f"{path}:24, POUTPUT/41: POUTPUT only names the variables that are a plant's outputs "
        "for Adams' linearization and control co-simulation; set aside"]
    assert [(c.analysis, c.end_time) for c in model.commands] == [("STATIC", 0.0),
                                                             ("TRANSIENT", 1.0)]
    assert model.graphics[30].type == "EXTERNAL"
    assert model.graphics[30].attrs["element"] == "block"
    res = model.run(integr_tol=1e-8)
    assert res.success and [s.success for s in res.statics] == [True]
    # the row at 0 is the static analysis' (at rest), then the transient's
    np.testing.assert_allclose(res.t, [0, 0.25, 0.5, 0.75, 1])
    np.testing.assert_allclose(res.request(50)[:, 1:3], [[0, 0], [0.0025, 0.01], [0.005, 0.01],
                                                        [0.0075, 0.01], [0.01, 0.01]],
                               atol=1e-10)


def test_an_msolve_models_label_and_the_settings_attributes_it_keeps():
    from pysolver.msolve import Equilibrium, Integrator, Model, Request, Variable
    model = Model(label="Bench  one", output="bench")
    integrator = Integrator(dae_index=3, kmax=5)
    Equilibrium(skip_mkeam=True, kinetic_energy_error=2e-5, type="STATIC")
    variable = Variable(function="TIME", penalty=10.0)
    Request(f1="TIME", results_name="r")
    assert (model.label, model.output) == ("Bench  one", "bench")
    assert (integrator.dae_index, variable.penalty, variable.penalty1) == (3, 10.0, None)
    text = model.adm()
    assert text.splitlines()[0] == "Bench one"
    assert "dae_index" not in text.lower() and "penalty" not in text.lower()
    loaded = model.load()
    assert loaded.static.max_ke_tol == 2e-5


def test_an_implicit_variable_is_refused_at_its_line():
    from pysolver.msolve import Model, Part, Variable
    model = Model()
    Part(ground=True)
    Variable(function="TIME", implicit=True)
    line = sys._getframe().f_lineno - 1
    with pytest.raises(DeckError) as err:
        model.adm()
    assert str(err.value) == (
        f"{__file__}:{line}, Variable id=1, attribute 'implicit': an implicit Variable (its "
        "function held at zero by a constraint or a penalty) is not supported: pysolver's "
        "variables are explicit, VARVAL(id) the function's value (docs/msolve.md)")


def test_the_command_prints_each_deck_warning_as_one_line(tmp_path):
    """Python's warning format showed a line of pysolver's code under each warning; the
    command prints `pysolver: warning: <file>:<line>, <statement>: ...` and nothing else."""
    path = tmp_path / "pendulum.adm"
    path.write_text(PENDULUM.format(extra="KINEMATICS/HMAX = 0.01"))
    out = subprocess.run([sys.executable, "-m", "pysolver", "check", str(path)],
                         capture_output=True, text=True, cwd=ROOT,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert out.returncode == 0
    assert out.stderr.splitlines() == [
        f"pysolver: warning: {path}:11, KINEMATICS: KINEMATICS only sets the tolerances of "
        "Adams' kinematic analysis; pysolver runs SIMULATE/KINEMATICS as a transient, with "
        "INTEGRATOR's settings (docs/adams.md, \"Commands\"); set aside"]


def test_a_library_warning_names_the_users_line(tmp_path):
    path = tmp_path / "pendulum.adm"
    path.write_text(PENDULUM.format(extra="KINEMATICS/HMAX = 0.01"))
    with pytest.warns(DeckWarning) as caught:
        pysolver.load(str(path))
    line = sys._getframe().f_lineno - 1
    assert (caught[0].filename, caught[0].lineno) == (__file__, line)


XML = """<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Body_Point id="2" cg_id="10" mass="1"/>
<Reference_Marker id="10" body_id="2"/>
{extra}
</Model></MotionSolve>
"""


@pytest.mark.parametrize("tag", NOT_MODELLED)
def test_xml_elements_not_modelled_say_so(tag):
    with pytest.raises(DeckError) as err:
        pysolver.loads(XML.format(extra=f'<{tag} id="1" i_marker_id="10" j_marker_id="1"/>'))
    assert (err.value.line, err.value.reason) == (
        6, f"<{tag}> is not supported: a MotionSolve element pysolver does not model "
        "(docs/deck-language.md, \"Not modelled\")")


def test_an_unknown_xml_element_gets_the_closest_name():
    with pytest.raises(DeckError) as err:
        pysolver.loads(XML.format(extra='<Force_Friction id="1"/>'))
    assert err.value.reason.startswith(
        "unknown element <Force_Friction>; did you mean <Force_JointFriction>? (known "
        "elements: Body_Point, Body_Rigid, ")


def test_plant_input_elements_are_set_aside():
    with pytest.warns(DeckWarning) as caught:
        model = pysolver.loads(XML.format(extra='<Control_PlantInput id="1" num_element="1"/>'))
    assert [w.message.reason for w in caught] == [
        "only names the variables that are a plant's inputs or outputs for linearization "
        "and control co-simulation; set aside"]
    assert model.run().success


def test_the_not_modelled_list_is_the_docs_and_apart_from_the_schema():
    """An element that becomes supported (added to SCHEMA) leaves NOT_MODELLED and the docs'
    list, which names exactly these."""
    assert not {n.lower() for n in NOT_MODELLED + SET_ASIDE} & {n.lower() for n in SCHEMA}
    page = (ROOT / "docs" / "deck-language.md").read_text()
    section = page.split("## Not modelled", 1)[1].split("\n## ", 1)[0]
    listed = set(re.findall(r"`((?:Body|Constraint|Control|Force|Reference)_\w+)`", section))
    assert listed == set(NOT_MODELLED) | set(SET_ASIDE)


#: Fkinev1's blocker, reduced: a slider in millimetres on a TRANSLATIONAL joint whose axis
#: (J's z) is global -y, gravity -9800 mm/s^2 along y, and the dataset's own JOINT IC line.
FKINEV1_IC = """slider
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = MILLIMETER, TIME = SECOND
PART/1, GROUND
MARKER/4, PART = 1, QP = 0, 0, 0, REULER = 0D, 90D, 0D
PART/2, MASS = 0.5, CM = 3, IP = 49, 23700, 23704
MARKER/3, PART = 2, REULER = 0D, 90D, 0D
JOINT/20
, TRANSLATIONAL
, I = 3
, J = 4
, IC = -0.1815, -146.9925875
ACCGRAV/JGRAV = -9800
REQUEST/1, F2 = DZ(3,4,4), F3 = VZ(3,4,4,4)
END
"""


def test_a_joints_ic_as_fkinev1_writes_it_starts_the_run(tmp_path):
    """Fkinev1 stopped at `IC = -0.1815, -146.9925875` on its JOINT/20 (trial 44); now the
    joint starts there: DZ(3, 4, 4) = -0.1815 mm and VZ = -146.99 mm/s at t = 0, then the
    slide along zJ = -y under gravity, d + v t + 9800 t^2 / 2, to 1e-6 mm."""
    adm = tmp_path / "fk.adm"
    adm.write_text(FKINEV1_IC)
    acf = tmp_path / "fk.acf"
    acf.write_text("fk.adm\n\nSIMULATE/DYNAMICS, END = 0.1, DTOUT = 0.01\nSTOP\n")
    res = pysolver.load(acf).run(integr_tol=1e-9)
    assert res.success, res.message
    q, t = res.request(1), res.t
    assert abs(q[0, 1] + 0.1815) < 1e-9 and abs(q[0, 2] + 146.9925875) < 1e-9
    assert np.abs(q[:, 1] - (-0.1815 - 146.9925875 * t + 4900 * t * t)).max() < 1e-6
