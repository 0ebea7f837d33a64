"""Write Andrews' squeezing mechanism (IFToMM A03; Test Set for IVP Solvers, problem
"andrews") with exact revolute joints as a MotionSolve XML deck.

Data: benchmarks/andrews.py (the project's penalty version of the same problem): the Test
Set's parameters, initial angles and its geometry (Hairer & Wanner, Solving ODEs II, sec.
VII.7), with the centres of mass and inertias that reproduce the Test Set's mass matrix.
benchmarks/joint_references.py reproduces the Test Set's PSIDE reference at t = 0.03 from
this same geometry with an independent planar solver (to 1.4e-9 rad), which checks the
geometry written here.

Deck: 7 bodies (ids 1..7 as in the Test Set, ground 100), each with its centre-of-mass
marker turned by the body angle (psi, a rotation about global z); 10 REVOLUTE joints about
global z at the joint points O, P, D (three: 2-3, 2-4, 2-6), B, E, A (two: 5-ground,
7-ground), F, each with the I marker on the first body of benchmarks/andrews.py's joint list
and the J marker on the second, both with global axes; the driving torque 0.033 N m on the
crank about z (Force_Scalar_TwoBody, Torque) and the spring c0 = 4530 N/m, l0 = 0.07785 m
between the point S on body 3 and C on ground (Force_Scalar_TwoBody, Force, positive
repels). No gravity. At rest at t = 0; 0.03 s. Post_Request 1 holds the seven body angles
AZ(cm_k) exactly as benchmarks/andrews.py's penalty deck, so andrews.error(res) and
andrews.angles_at_end(res) apply to this deck's results unchanged.

As a planar mechanism with three independent loops written with 3D revolutes it has
9 redundant equations (42 coordinates, 50 equations, 1 DOF).

Run: ``python decks/joints/make_a03.py [-o PATH]`` (default iftomm_a03_andrews.xml here).
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "benchmarks"))

import andrews  # noqa: E402

JOINTS = [("O", 1, 100), ("P", 1, 2), ("D", 2, 3), ("D", 2, 4), ("D", 2, 6), ("B", 3, 100),
          ("E", 4, 5), ("A", 5, 100), ("A", 7, 100), ("F", 6, 7)]


def deck(tol=1e-9, end=0.03, dt=1e-4):
    p = andrews.P
    angles, com, pts = andrews.geometry()
    els = ['<Units mass="KILOGRAM" length="METER" time="SECOND" force="NEWTON"/>',
           '<Body_Rigid id="100" isground="TRUE"/>']
    mid = [1000]

    def marker(body, xy, psi=0.0, label=""):
        mid[0] += 1
        rot = f' psi="{float(psi)!r}" theta="0" phi="0"' if psi else ""
        els.append(f'<Reference_Marker id="{mid[0]}" body_id="{body}" pos_x="{float(xy[0])!r}" '
                   f'pos_y="{float(xy[1])!r}" pos_z="0"{rot} label="{label}"/>')
        return mid[0]

    cm = {}
    for k in range(1, 8):
        cm[k] = marker(k, com[k], angles[k], f"body {k} cm")
        ik = p[f"i{k}"]
        els.append(f'<Body_Rigid id="{k}" cg_id="{cm[k]}" mass="{p[f"m{k}"]!r}" '
                   f'inertia_xx="{ik!r}" inertia_yy="{ik!r}" inertia_zz="{ik!r}" '
                   f'label="body {k}"/>')
    for jid, (name, bi, bj) in enumerate(JOINTS, start=1):
        mi = marker(bi, pts[name], label=f"{name} on {bi} (I)")
        mj = marker(bj, pts[name], label=f"{name} on {'ground' if bj == 100 else bj} (J)")
        els.append(f'<Constraint_Joint id="{jid}" label="{name} {bi}-{bj}" type="REVOLUTE" '
                   f'i_marker_id="{mi}" j_marker_id="{mj}"/>')
    crank = marker(1, pts["O"], label="O on the crank (torque I)")
    ground = marker(100, pts["O"], label="O on ground (torque J)")
    els.append(f'<Force_Scalar_TwoBody id="1" label="driving torque" type="Torque" '
               f'i_marker_id="{crank}" j_marker_id="{ground}" val="{p["mom"]!r}"/>')
    sp = marker(3, pts["S"], label="spring end S on body 3")
    sc = marker(100, pts["C"], label="spring anchor C on ground")
    els.append(f'<Force_Scalar_TwoBody id="2" label="spring" type="Force" i_marker_id="{sp}" '
               f'j_marker_id="{sc}" expr="-{p["c0"]!r}*(DM({sp},{sc}) - {p["l0"]!r})"/>')
    chans = " ".join(f'expr{k}="AZ({cm[k]})"' for k in range(1, 8))
    names = " ".join(f'name{k}="theta{k}"' for k in range(1, 8))
    els.append(f'<Post_Request id="1" {chans} {names}/>')
    els.append(f'<Param_Transient integr_tol="{tol!r}"/>')
    head = """<?xml version="1.0"?>
<!-- Andrews' squeezing mechanism with exact joints (IFToMM A03 / Test Set for IVP solvers),
     written by decks/joints/make_a03.py from benchmarks/andrews.py's data (its docstring
     has the model and every decision; do not edit by hand). 7 planar bodies, 10 REVOLUTE
     joints about global z (9 redundant equations in 3D), driving torque 0.033 N m, spring
     c0 = 4530 N/m, l0 = 0.07785 m, no gravity, at rest, 0.03 s.
     Compare: channels 1-7 (body angles AZ) through benchmarks/andrews.py's angles_at_end()
     and error() against the Test Set reference at t = 0.03 (shared/reference/numerics.md
     section 2; beta = 15.81077119629904, Theta = -15.75637105984298, ...); this project's
     independent exact-joint solution (benchmarks/data/joint_references.json,
     iftomm_a03_andrews) differs from the Test Set's by up to 1.4e-9 rad, so errors below
     about 2e-9 rad against the Test Set are not meaningful. -->
<MotionSolve>
  <Model>
"""
    return (head + "\n".join("    " + e for e in els) + "\n  </Model>\n"
            f'  <Simulate analysis_type="Transient" end_time="{end!r}" print_interval="{dt!r}"/>\n'
            "</MotionSolve>\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description="Andrews' mechanism deck writer")
    ap.add_argument("-o", "--out", default=os.path.join(HERE, "iftomm_a03_andrews.xml"))
    a = ap.parse_args(argv)
    with open(a.out, "w") as f:
        f.write(deck())
    print("wrote", a.out)


if __name__ == "__main__":
    main()
