"""Trial 45's failures of called routines: a SENSUB's own error message, a NaN or None from a
routine on a branch of the state (status -700 / -400 at once, not a million steps)."""
import pysolver

SCENE = '''from pysolver.msolve import *
{routine}
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[2, 0, 0])
POINT_MASS(2, MASS=1.0, CM=10)
{elements}
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT={dtout})
'''


def _run(routine, elements, dtout=0.1):
    return pysolver.loads(SCENE.format(routine=routine, elements=elements, dtout=dtout),
                          fmt="py").run()


SPRING = 'SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="-10*(DM(10,1)-1)")'


def test_a_sensubs_error_is_reported_with_its_message():
    routine = ('def sen(id, time, par, npar, iflag):\n'
               '    x = float(py_sysfnc("DX", [10])[0])\n'
               '    if iflag == 0 and time > 0.5:\n'
               '        py_errmes(1, "sensor failed", id, "STOP")\n'
               '    return x\n')
    res = _run(routine, SPRING + '\nSENSOR(3, FUNCTION="USER(10)", ROUTINE=sen, VALUE=-5, '
                                 'OPERATOR="LT")\nREQUEST(2, F1="DX(10)")')
    assert (res.success, res.status) == (False, -400)
    assert res.message.startswith("user subroutine (id 3): sen: sensor failed (id 3) "
                                  "(called at t = 0.5")


NAN_FORCE = ('def sfo(id, time, par, npar, dflag, iflag):\n'
             '    x = float(py_sysfnc("DX", [10])[0])\n'
             '    return {bad} if x < 1.0 else -10*x\n')
NAN_ELEMENTS = ('SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="USER(10)", ROUTINE=sfo)\n'
                'REQUEST(1, F1="DX(10)")\nINTEGRATOR(ERROR=1e-8)')


def test_a_nan_from_a_routine_on_a_state_branch_ends_the_run_as_an_expressions_does():
    """x = 2 cos(sqrt(10) t) reaches 1 at t = acos(1/2) / sqrt(10) = 0.331153: -700 there,
    naming the element and the routine, within the expression version's steps (it took
    500,075 steps to max_num_steps before)."""
    res = _run(NAN_FORCE.format(bad='float("nan")'), NAN_ELEMENTS, 0.05)
    assert (res.success, res.status) == (False, -700)
    assert res.message.startswith("IDA failed at t = 0.331153 after a non-finite value (nan) "
                                  "in Force_Scalar_TwoBody 1: USER(10) -> sfo (a Python "
                                  "callable) (user subroutine sfo), at t = 0.33115")
    assert res.stats["steps"] < 200


def test_none_from_a_routine_is_the_routines_error():
    res = _run(NAN_FORCE.format(bad="None"), NAN_ELEMENTS, 0.05)
    assert (res.success, res.status) == (False, -400)
    assert res.message.startswith("user subroutine (id 1): sfo: returned None, not a number "
                                  "(called at t = 0.33")
