"""Write the IFToMM A02 N-four-bar mechanism as a MotionSolve XML deck.

Spec (IFToMM Library of Computational Benchmark Problems, problem A02, "N four-bar
mechanism", http://lim.ii.udc.es/mbsbenchmark/dist/A02/A02_specification.xml): 2N+1 links
of 1 m with a uniformly distributed mass of 1 kg, gravity 9.81 N/kg in -y, N = 40, a
dynamic simulation of 20 s; at t = 0 the mechanism is in the figure's position (cranks
vertical, couplers horizontal at y = 1) and the x velocity of point B0 is 1 m/s. Reported:
the position and velocity of B0 with 400 output steps; allowed errors 1e-1 (low) and 1e-3
(high precision), threshold 1e-3. When the mechanism is horizontal the DOF jump from 1 to
N+1 (singular configurations).

Layout (as in the OpenSim and simEngine3D implementations of A02): crank i (i = 0..N)
pivots on ground at (i, 0, 0) and ends at (i, 1, 0); coupler j (j = 1..N) joins the tops
of cranks j-1 and j. B0 is the top of crank 0. All revolute axes along global z; J markers
on ground / on the crank, I markers on the body further from ground.

Initial velocities (consistent with the joints): every crank turns at -1 rad/s about z
(so B0 moves at +1 m/s in x), its centre moves at +0.5 m/s in x; couplers translate at
+1 m/s in x.

Decisions: a uniform slender link has zero inertia about its own axis; MotionSolve needs
positive principal inertias, so the axial inertia is 1e-4 kg m^2 (the planar motion never
turns a link about its axis). Transverse inertias m L^2 / 12.

Run: ``python decks/joints/make_a02.py`` writes iftomm_a02_fourbar.xml (all joints
REVOLUTE: 121 revolutes, 605 equations on 486 coordinates, 120 of them redundant, as a
MotionSolve user would write it) and iftomm_a02_fourbar_inline.xml (each coupler's right
end held by an INLINE primitive instead: 485 independent equations, no redundancy, the same
motion). ``--n N`` for a smaller N, ``--inline`` / ``-o PATH`` to write one file.
"""
import argparse
import os

HERE = os.path.dirname(os.path.abspath(__file__))
AXIAL = 1e-4
TRANSVERSE = 1.0 / 12


def deck(n=40, inline=False, end=20.0, dt=0.05, tol=1e-8):
    els = []
    add = els.append
    closing = "INLINE" if inline else "REVOLUTE"
    add('<Units mass="KILOGRAM" length="METER" time="SECOND" force="NEWTON"/>')
    add('<Body_Rigid id="1" isground="TRUE"/>')
    add('<Reference_Marker id="1" body_id="1" label="global"/>')
    add('<Force_Gravity grav_x="0" grav_y="-9.81" grav_z="0"/>')
    jid = 0

    def joint(kind, i_m, j_m, label):
        nonlocal jid
        jid += 1
        add(f'<Constraint_Joint id="{jid}" label="{label}" type="{kind}" '
            f'i_marker_id="{i_m}" j_marker_id="{j_m}"/>')

    # cranks: body 2 + i, markers 10 * body + (0 cm, 1 bottom, 2 top)
    for i in range(n + 1):
        b = 2 + i
        add(f'<Reference_Marker id="{1000 + i}" body_id="1" pos_x="{i}" pos_y="0" '
            f'label="ground pivot {i} (J)"/>')
        add(f'<Reference_Marker id="{10 * b}" body_id="{b}" pos_x="{i}" pos_y="0.5" '
            f'label="crank {i} cm"/>')
        add(f'<Reference_Marker id="{10 * b + 1}" body_id="{b}" pos_x="{i}" pos_y="0" '
            f'label="crank {i} bottom (I)"/>')
        add(f'<Reference_Marker id="{10 * b + 2}" body_id="{b}" pos_x="{i}" pos_y="1" '
            f'label="crank {i} top{" = B0" if i == 0 else ""} (J)"/>')
        add(f'<Body_Rigid id="{b}" cg_id="{10 * b}" mass="1" inertia_xx="{TRANSVERSE!r}" '
            f'inertia_yy="{AXIAL!r}" inertia_zz="{TRANSVERSE!r}" v_ic_x="0.5" w_ic_z="-1" '
            f'label="crank {i}"/>')
        joint("REVOLUTE", 10 * b + 1, 1000 + i, f"ground-crank {i}")
    # couplers: body 1000 + j, markers 10 * body + (0 cm, 1 left, 2 right)
    for j in range(1, n + 1):
        b = 1000 + j
        add(f'<Reference_Marker id="{10 * b}" body_id="{b}" pos_x="{j - 0.5!r}" pos_y="1" '
            f'label="coupler {j} cm"/>')
        add(f'<Reference_Marker id="{10 * b + 1}" body_id="{b}" pos_x="{j - 1}" pos_y="1" '
            f'label="coupler {j} left (I)"/>')
        add(f'<Reference_Marker id="{10 * b + 2}" body_id="{b}" pos_x="{j}" pos_y="1" '
            f'label="coupler {j} right (I)"/>')
        add(f'<Body_Rigid id="{b}" cg_id="{10 * b}" mass="1" inertia_xx="{AXIAL!r}" '
            f'inertia_yy="{TRANSVERSE!r}" inertia_zz="{TRANSVERSE!r}" v_ic_x="1" '
            f'label="coupler {j}"/>')
        joint("REVOLUTE", 10 * b + 1, 10 * (2 + j - 1) + 2, f"crank {j - 1}-coupler {j}")
        joint(closing, 10 * b + 2, 10 * (2 + j) + 2, f"coupler {j}-crank {j}")
    add('<Post_Request id="1" expr1="DX(22)" expr2="DY(22)" expr3="VX(22)" expr4="VY(22)" '
        'expr5="AZ(21,1000)" name1="B0_x" name2="B0_y" name3="B0_vx" name4="B0_vy" '
        'name5="crank0_rotation"/>')
    add(f'<Param_Transient integr_tol="{tol!r}"/>')
    nb = 2 * n + 1
    neq = 5 * (n + 1) + 5 * n + (2 if inline else 5) * n
    head = f"""<?xml version="1.0"?>
<!-- IFToMM A02 N-four-bar mechanism, N = {n}, written by decks/joints/make_a02.py
     (its docstring has the spec and every decision; do not edit by hand).
     Source: http://lim.ii.udc.es/mbsbenchmark/dist/A02/A02_specification.xml : 2N+1 = {nb}
     links of 1 m and 1 kg (uniform; transverse inertia 1/12 kg m^2, axial {AXIAL!r} by
     decision), gravity -9.81 y, 20 s, B0 (top of crank 0, marker 22) starts at +1 m/s in x.
     Cranks: bodies 2..{n + 2} pivoted on ground at x = 0..{n}; couplers: bodies 1001..{1000 + n}.
     Joints: {"each coupler's right end INLINE (x, y held, z free): no redundancy" if inline
              else "all REVOLUTE about global z"}; {neq} equations on {6 * nb} coordinates
     ({neq - (6 * nb - 1)} redundant), 1 DOF away from the horizontal singular positions.
     Compare: B0 position and velocity (channels 1-4) against iftomm_a02_fourbar in
     benchmarks/data/joint_references.json (exact 1-DOF solution of the parallelogram
     branch, 401 outputs every 0.05 s); spec tolerances 1e-1 / 1e-3. The singular horizontal
     position is first reached at t = 0.7216 s; a solver that switches branch there departs
     from the reference. -->
<MotionSolve>
  <Model>
"""
    body = "\n".join("    " + e for e in els)
    tail = (f'\n  </Model>\n  <Simulate analysis_type="Transient" end_time="{end!r}" '
            f'print_interval="{dt!r}"/>\n</MotionSolve>\n')
    return head + body + tail


def main(argv=None):
    ap = argparse.ArgumentParser(description="IFToMM A02 deck writer")
    ap.add_argument("--n", type=int, default=40)
    ap.add_argument("--inline", action="store_true")
    ap.add_argument("-o", "--out")
    a = ap.parse_args(argv)
    if a.out or a.inline or a.n != 40:
        out = a.out or os.path.join(HERE, f"iftomm_a02_fourbar{'_inline' if a.inline else ''}"
                                          f"{'' if a.n == 40 else f'_n{a.n}'}.xml")
        with open(out, "w") as f:
            f.write(deck(a.n, a.inline))
        print("wrote", out)
        return
    for inline, name in ((False, "iftomm_a02_fourbar.xml"),
                         (True, "iftomm_a02_fourbar_inline.xml")):
        with open(os.path.join(HERE, name), "w") as f:
            f.write(deck(a.n, inline))
        print("wrote", name)


if __name__ == "__main__":
    main()
