"""Scenes shared by the tests and the benchmarks: deck generators, exact solutions and the
reference values they are checked against. They live with the tests, which need nothing from
benchmarks/; benchmark scripts import them through benchmarks/scenes.py."""
import math
import pathlib

import numpy as np

DECKS = pathlib.Path(__file__).resolve().parent.parent / "decks"

#: Bilateral penalty on a point mass under gravity, an exact damped linear oscillator: mass,
#: penalty, penalty1, gravity, initial height and velocity.


def chain_deck(n, penalty=1e4, penalty1=20.0, end_time=1.0, tol=1e-6):
    """A chain of `n` point masses linked by bilateral distance penalties, the first one
    pinned to ground, released horizontally under gravity (6 n states, sparse coupling)."""
    els = ['<Body_Rigid id="1" isground="TRUE"/>', '<Reference_Marker id="1" body_id="1"/>',
           '<Force_Gravity grav_z="-9.81"/>']
    for i in range(n):
        bid, mid = 100 + i, 1000 + i
        els.append(f'<Reference_Marker id="{mid}" body_id="{bid}" pos_x="{0.1 * (i + 1)}"/>')
        els.append(f'<Body_Point id="{bid}" cg_id="{mid}" mass="0.1"/>')
        prev = 1 if i == 0 else mid - 1
        els.append(f'<Force_Penalty id="{i + 1}" expr="DM({mid},{prev}) - 0.1" '
                   f'penalty="{penalty}" penalty1="{penalty1}"/>')
    last = 1000 + n - 1
    els.append(f'<Post_Request id="1" expr1="DX({last})" expr2="DZ({last})" '
               f'expr3="PFORCE(1)" name1="x_end" name2="z_end" name3="tension_1"/>')
    els.append(f'<Param_Transient integr_tol="{tol}"/>')
    return ("<MotionSolve><Model>\n" + "\n".join(els) + "\n</Model>\n"
            f'<Simulate analysis_type="Transient" end_time="{end_time}" print_interval="0.01"/>\n'
            "</MotionSolve>\n")


def rigid_chain_deck(n, end_time=0.05):
    """A chain of `n` rigid bodies, each turned differently (3-1-3 angles that change along
    the chain), joined end to end by three penalties each (DX, DY, DZ of the joint markers in
    the previous body's end marker), the first to ground, under gravity (13 n states)."""
    els = ['<Body_Rigid id="1" isground="TRUE"/>', '<Reference_Marker id="1" body_id="1"/>',
           '<Force_Gravity grav_z="-9.81"/>']
    for i in range(n):
        b, cg = 100 + i, 1000 + 3 * i
        els.append(f'<Reference_Marker id="{cg}" body_id="{b}" pos_x="{0.2 * i + 0.1}" '
                   f'psi="{0.1 * i}" theta="0.2"/>')
        els.append(f'<Reference_Marker id="{cg + 1}" body_id="{b}" pos_x="{0.2 * i}"/>')
        els.append(f'<Reference_Marker id="{cg + 2}" body_id="{b}" pos_x="{0.2 * i + 0.2}"/>')
        els.append(f'<Body_Rigid id="{b}" cg_id="{cg}" mass="0.5" inertia_xx="0.01" '
                   'inertia_yy="0.02" inertia_zz="0.02"/>')
        prev = 1 if i == 0 else cg - 1
        for k, f in enumerate(("DX", "DY", "DZ")):
            els.append(f'<Force_Penalty id="{10 * i + k + 1}" expr="{f}({cg + 1},{prev},{prev})" '
                       'penalty="1e4" penalty1="20"/>')
    last = 1000 + 3 * (n - 1)
    els.append(f'<Post_Request id="1" expr1="WX({last})" expr2="AX({last})" expr3="DZ({last})"/>')
    return ("<MotionSolve><Model>\n" + "\n".join(els) + "\n</Model>\n"
            f'<Simulate analysis_type="Transient" end_time="{end_time}" print_interval="0.01"/>'
            "\n</MotionSolve>\n")


#: The stiff penalty pendulum of issue 5 (decks/stiff_penalty_pendulum.xml): 1 kg on a bilateral
#: penalty rod (k = 1e8, c = 2e4, critical), released horizontally, 10 s, outputs every 0.01 s.
PENDULUM = (DECKS / "stiff_penalty_pendulum.xml").read_text()


M, K, C, G, Z0, V0 = 2.0, 100.0, 4.0, 9.81, 1.2, 0.5

OSCILLATOR = f"""<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="10" body_id="2" pos_z="{Z0}"/>
  <Body_Point id="2" cg_id="10" mass="{M}" v_ic_z="{V0}"/>
  <Force_Gravity grav_z="-{G}"/>
  <Force_Penalty id="1" expr="DZ(10) - 1" penalty="{K}" penalty1="{C}"/>
  <Post_Request id="1" expr1="DZ(10)" expr2="VZ(10)" expr3="PFORCE(1)"/>
</Model>
<Simulate analysis_type="Transient" end_time="3.0" print_interval="0.01"/>
</MotionSolve>"""


def oscillator_exact(t):
    """Position and velocity of OSCILLATOR at times t, in closed form."""
    w0 = np.sqrt(K / M)
    zeta = C / (2 * np.sqrt(K * M))
    wd = w0 * np.sqrt(1 - zeta ** 2)
    zeq = 1 - M * G / K
    x0 = Z0 - zeq
    a, b = x0, (V0 + zeta * w0 * x0) / wd
    decay = np.exp(-zeta * w0 * t)
    z = zeq + decay * (a * np.cos(wd * t) + b * np.sin(wd * t))
    v = decay * ((-zeta * w0 * a + wd * b) * np.cos(wd * t) + (-zeta * w0 * b - wd * a) * np.sin(wd * t))
    return z, v


def rest_penetration(k, mg, s):
    """Root of 2 k g STEP(g, 0, 0, s, 1) = m grav by bisection."""
    lo, hi = 0.0, s
    for _ in range(200):
        g = 0.5 * (lo + hi)
        d = g / s
        if 2 * k * g * d * d * (3 - 2 * d) > mg:
            hi = g
        else:
            lo = g
    return 0.5 * (lo + hi)


def ball(sensors, z0=10.0, end=2.0, dt=0.1, extra="", tol=1e-10, more=""):
    """A point mass falling from z0 under gravity, with the given sensor elements."""
    return f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="10" body_id="2" pos_z="{z0}"/>
      <Body_Point id="2" cg_id="10" mass="1"/><Force_Gravity grav_z="-{G}"/>{extra}
      {sensors}
      <Post_Request id="1" expr1="DZ(10)" expr2="VZ(10)" expr3="TIME"/>
      <Param_Transient integr_tol="{tol}"/></Model>
      <Simulate analysis_type="Transient" end_time="{end}" print_interval="{dt}"/>{more}
      </MotionSolve>"""


def contact(zero_crossing, z0=1.0, **options):
    """decks/contact_onset_zero_crossing.xml dropped from z0 (zero_crossing None: without it):
    the first contact event's time, its output row, and the Result."""
    import pysolver
    text = (DECKS / "contact_onset_zero_crossing.xml").read_text()
    text = text.replace('zero_crossing="0.01"', f'zero_crossing="{zero_crossing}"'
                        if zero_crossing else "").replace('pos_z="1"', f'pos_z="{z0}"')
    text = text.replace('end_time="0.6"', f'end_time="{math.sqrt(2 * z0 / G) + 0.05}"')
    res = pysolver.loads(text).run(**options)
    (ev,) = [e for e in res.events if e.sensor == 1][:1]
    return ev.time, res.request(1)[list(res.t).index(ev.time)], res


# -- seed example 3 with its two penalties as user subroutines, in every form ----------------

#: The line constraint g = 1 + s x - z of seed example 3 as a Python PFOSUB: USER(marker, s).
LINES_PFOSUB = '''def PFOSUB(id, time, par, npar, dflag, iflag):
    ipar = [int(par[0])]
    x = py_sysfnc("DX", ipar)[0]
    z = py_sysfnc("DZ", ipar)[0]
    return 1 + par[1] * x - z
'''

#: The same g written with a state-dependent branch: traced into IF(...).
LINES_BRANCHY = '''def PFOSUB(id, time, par, npar, dflag, iflag):
    ipar = [int(par[0])]
    x = py_sysfnc("DX", ipar)[0]
    z = py_sysfnc("DZ", ipar)[0]
    if par[1] * x >= 0:
        return 1 + abs(x) - z
    return 1 - abs(x) - z
'''

#: The same g through NumPy (a conversion to float), which cannot be traced.
LINES_NUMPY = '''def PFOSUB(id, time, par, npar, dflag, iflag):
    import numpy as np
    ipar = [int(par[0])]
    x, z = np.array([py_sysfnc("DX", ipar)[0], py_sysfnc("DZ", ipar)[0]], dtype=float)
    return float(1 + par[1] * x - z)
'''

#: The same g in C (c_sysary TDISP), built by usersub_library().
LINES_C = r'''#include "pysolver_usersub.h"

void PFOSUB(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int m = (int)par[0], n, err;
  double p[3];
  c_sysary("TDISP", &m, 1, p, &n, &err);
  *value = 1.0 + par[1] * p[0] - p[2];
}
'''

#: The NumPy form giving its partials in DX and DZ with py_syspar: not differenced in them.
LINES_NUMPY_SYSPAR = LINES_NUMPY.replace(
    "    return float(1 + par[1] * x - z)",
    "    py_syspar('DX', ipar, [par[1]])\n    py_syspar('DZ', ipar, [-1.0])\n"
    "    return float(1 + par[1] * x - z)")

#: The C form giving its partials in TDISP with c_syspar (Adams' SYSPAR).
LINES_C_SYSPAR = LINES_C.replace(
    "  *value = 1.0 + par[1] * p[0] - p[2];\n",
    "  *value = 1.0 + par[1] * p[0] - p[2];\n"
    "  double dg[3] = {par[1], 0.0, -1.0};\n"
    "  c_syspar(\"TDISP\", &m, 1, dg, 3, &err);\n")

#: ... and in its time argument as well (c_syspar "TIME"): not stepped in time either.
LINES_C_SYSPAR_TIME = LINES_C_SYSPAR.replace(
    "  c_syspar(\"TDISP\", &m, 1, dg, 3, &err);\n",
    "  c_syspar(\"TDISP\", &m, 1, dg, 3, &err);\n"
    "  double dt = 0.0;\n"
    "  c_syspar(\"TIME\", NULL, 0, &dt, 1, &err);\n")

USERSUB_FORMS = ("expression", "script", "callable", "branchy", "untraceable",
                 "untraceable_syspar", "c", "c_syspar", "c_syspar_time")


def usersub_library(folder, source=LINES_C, name="subs"):
    """Build a user subroutine library with the system C compiler; None when there is none."""
    import shutil
    import subprocess

    import pysolver
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        return None
    folder = pathlib.Path(folder)
    (folder / f"{name}.c").write_text(source)
    out = folder / f"{name}.so"
    subprocess.run([cc, "-O2", "-shared", "-fPIC", f"-I{pysolver.get_include()}",
                    str(folder / f"{name}.c"), "-o", str(out)], check=True)
    return out


def lines_deck(form, folder):
    """Seed example 3 (decks/particle_between_lines.py) with both penalties in one form:
    ``(deck text, fmt)``. Forms: expression, script (a Python script, traced), callable (a
    function in the deck, traced), branchy (a function with a state-dependent branch, traced
    into IF), untraceable (a function through NumPy, called from the kernel), c (a C library,
    called from the kernel), untraceable_syspar and c_syspar (the same, giving their
    partials with py_syspar / c_syspar) and c_syspar_time (giving the partial in time too)."""
    text = (DECKS / "particle_between_lines.py").read_text()
    if form == "expression":
        return text, "py"
    folder = pathlib.Path(folder)
    if form == "script":
        (folder / "lines.py").write_text(LINES_PFOSUB)
        how = f"SCRIPT={str(folder / 'lines.py')!r}"
    elif form in ("c", "c_syspar", "c_syspar_time"):
        lib = usersub_library(folder, *{"c": (LINES_C, "subs"),
                                        "c_syspar": (LINES_C_SYSPAR, "subs_syspar"),
                                        "c_syspar_time": (LINES_C_SYSPAR_TIME,
                                                          "subs_syspar_time")}[form])
        if lib is None:
            return None, "py"
        how = f"ROUTINE={str(lib) + '::PFOSUB'!r}"
    else:
        source = {"callable": LINES_PFOSUB, "branchy": LINES_BRANCHY,
                  "untraceable": LINES_NUMPY, "untraceable_syspar": LINES_NUMPY_SYSPAR}[form]
        text = text.replace("PART(1,", source.replace("def PFOSUB", "def lines") + "\nPART(1,")
        how = "ROUTINE=lines"
    for k, sign in ((1, "1"), (2, "-1")):
        expr = "1+DX(10)-DZ(10)" if k == 1 else "1-DX(10)-DZ(10)"
        old = f'FUNCTION="{expr}"'
        assert old in text
        text = text.replace(old, f'FUNCTION="USER(10, {sign})", {how}')
    return text, "py"


# -- a 1 kg point mass at x = 2 on a spring to ground, its force a C SFOSUB -----------------

#: The spring's SFOSUB, stiffness %s N/m: USER(marker).
SPRING_SFOSUB = r'''#include "pysolver_usersub.h"
void SFOSUB(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int m = (int)par[0], err;
  double x;
  c_sysfnc("DX", &m, 1, &x, &err);
  *value = -%s * (x - 1.0);
}
'''

#: The mass on that spring as a Python deck; {routine}: the SFORCE's ROUTINE.
SPRING_PY = '''from pysolver.msolve import *
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[2, 0, 0])
POINT_MASS(2, MASS=1.0, CM=10)
SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="USER(10)", ROUTINE="{routine}")
REQUEST(1, F1="DX(10)")
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.1)
'''

#: ... and as XML; {usersub}: the Force_Scalar_TwoBody's library attributes.
SPRING_XML = '''<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="10" body_id="2" pos_x="2"/>
<Body_Point id="2" cg_id="10" mass="1.0"/>
<Force_Scalar_TwoBody id="1" type="Force" i_marker_id="10" j_marker_id="1"
  {usersub} usrsub_param_string="USER(10)"/>
<Post_Request id="1" expr1="DX(10)"/>
</Model><Simulate analysis_type="Transient" end_time="1" print_interval="0.1"/></MotionSolve>
'''
