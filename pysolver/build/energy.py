"""KE(id): the kinetic energy of body id (0: every body), lowered to tape instructions.

KE = (m |v|^2 + w^T I w) / 2 per body, v the centre of mass's velocity (VX.. of its cg marker),
w its angular velocity in the cg marker's axes (WX(cg, 0, cg)..) and I its inertia there, in
the deck's force times length units (the model's mass length^2/time^2 divided by the
force-unit scale: N mm in a kg/mm/s/N deck). The masses and inertias are constants named
``KE/<body>/...`` that a sweep's change of the body's mass or inertia updates
(pysolver.build.params), so the energy follows the run's numbers.
"""
from .bindings import lib


def energy_paths(body):
    """The constants KE keeps for `body`: its mass and the nine entries of its inertia."""
    return [f"KE/{body.id}/mass"] + [f"KE/{body.id}/inertia{k}" for k in range(9)]


def lower_energy(comp, tape, bid):
    """Slot of KE(bid) on `tape`."""
    model = comp.model
    bodies = ([b for b in model.bodies.values() if b.kind != "ground"] if bid == 0 else
              [model.bodies[bid]] if model.bodies[bid].kind != "ground" else [])
    mul, add = lib.PS_OP_MUL, lib.PS_OP_ADD
    total = tape.const(0.0)
    for b in sorted(bodies, key=lambda b: b.id):
        paths = energy_paths(b)
        v = [comp.measure(tape, n, [b.cg]) for n in ("VX", "VY", "VZ")]
        v2 = tape.op(add, tape.op(mul, v[0], v[0]),
                     tape.op(add, tape.op(mul, v[1], v[1]), tape.op(mul, v[2], v[2])))
        part = tape.op(mul, tape.param(paths[0], b.mass), v2)
        if b.kind == "rigid":
            w = [comp.measure(tape, n, [b.cg, 0, b.cg]) for n in ("WX", "WY", "WZ")]
            for i in range(3):
                for j in range(3):
                    Iij = tape.param(paths[1 + 3 * i + j], float(b.inertia[i, j]))
                    part = tape.op(add, part, tape.op(mul, Iij, tape.op(mul, w[i], w[j])))
        total = tape.op(add, total, part)
    return tape.op(mul, tape.const(0.5 / model.force_scale), total)
