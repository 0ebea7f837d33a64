"""Messages for a non-finite value the kernel found (psData.bad_kind, set in C only on that
failure path): which element, its expression, the time and the state."""
import math
from types import SimpleNamespace

import numpy as np

from .. import catalogue
from ..build.bindings import lib

_SHOWN = 12        # state entries quoted in a message


def _texts(e):
    if hasattr(e, "type"):                # a joint: its equations are its type's
        return [f"{e.type} I={e.i} J={e.j}"]
    return [e.text] if hasattr(e, "text") else list(e.texts)


def _element(model, kernel, kind, index):
    """(type name, record) of the element a PS_BAD_* value and index name: a row of the
    kernel's element table, or a record of a kind diagnosed on its own (sensors, by id)."""
    if kind == lib.PS_BAD_ELEMENT:
        name, eid, *_ = kernel.elements[index]
        e = catalogue.ELEMENT_OF_KIND[name]
        if name == "sforce" and eid < 0:          # a Force_SpringDamper's law
            return "Force_SpringDamper", SimpleNamespace(id=-eid, text=model.sforces[eid].text)
        if name == "vforce" and model.vforces[eid].owner:   # a bushing's, field's or beam's
            tag, oid = model.vforces[eid].owner
            return tag, SimpleNamespace(id=oid, texts=model.vforces[eid].texts)
        if name == "turn":                        # the tracked angle of a joint, coupler, spring
            return "tracked angle of element", SimpleNamespace(
                id=eid, text="atan2(sin(theta - s), cos(theta - s))")
        tag = kernel.motion_tags[eid] if name == "motion" else e.tags[0]
        return tag, getattr(model, e.table)[eid]
    e = next(e for e in catalogue.ELEMENTS if e.bad and getattr(lib, e.bad) == kind)
    table = getattr(model, e.table)
    return e.tags[0], table[sorted(table)[index]]


def _state(names, y):
    shown = ", ".join(f"{n} = {v:.6g}" for n, v in zip(names[:_SHOWN], y[:_SHOWN]))
    more = len(names) - _SHOWN
    return shown + (f", ... ({more} more)" if more > 0 else "")


def describe(model, kernel):
    """Return the message for the kernel's last non-finite value, or None if there was none:
    the element and its expression, the time and the state of that evaluation."""
    d = kernel.d
    kind, index, value = d.bad_kind, d.bad_index, d.bad_value
    if kind == lib.PS_BAD_NONE:
        return None
    names = kernel.layout.names
    t, y = kernel.bad_state
    if kind == lib.PS_BAD_DIRECTION:
        return _no_direction(model, kernel, index, value, t)
    if kind in (lib.PS_BAD_STATE, lib.PS_BAD_RATE):
        what = f"state {names[index]}" + (" rate" if kind == lib.PS_BAD_RATE else "")
    elif kind == lib.PS_BAD_RESIDUAL:
        what = (f"the residual of {names[index]}" if index >= 0 else "the residual") + \
            " (no element's value is: a mass, inertia or a product overflowed)"
    elif kind == lib.PS_BAD_JACOBIAN:
        n = len(names)
        entry = (f"d res({names[index // n]}) / d {names[index % n]}" if index >= 0
                 else "an entry")
        what = (f"the Jacobian, {entry} (a derivative of an expression is infinite, such as "
                f"SQRT or ACOS at the end of its domain)")
    else:
        name, e = _element(model, kernel, kind, index)
        what = f"{name} {e.id}: " + "; ".join(_texts(e))
        if getattr(e, "usersub", None) is not None:
            what += f" (user subroutine {e.usersub.label})"
    number = "nan" if math.isnan(value) else f"{value:g}"
    noun = "derivative" if d.bad_partial else "value"
    return (f"non-finite {noun} ({number}) in {what}, at t = {t:.9g}; "
            f"state: {_state(names, y)}")



def _no_direction(model, kernel, index, value, t):
    """The message for a translational force whose markers coincide while it is not 0
    (PS_BAD_DIRECTION): the line from J to I, along which it acts, has no direction there."""
    name, e = _element(model, kernel, lib.PS_BAD_ELEMENT, index)
    sf = model.sforces[kernel.elements[index][1]]
    return (f"force with no direction in {name} {e.id} ({e.text}): its markers I = {sf.i} "
            f"and J = {sf.j} coincide (DM = 0) while its force is {value:g}, at t = {t:.9g}; "
            "a translational force acts along the line from J to I, which has no direction "
            "there: place the markers apart, or give a force that is 0 where they meet "
            "(docs/deck-language.md, \"Coincident markers\")")


def restart_reason(model, kernel, code):
    """Why a consistent restart (ps_restart_consistent) returned `code`: the constraints
    singular, the positions unassemblable, or the kernel's diagnosis of a non-finite value."""
    why = {lib.PS_ERR_SINGULAR: "the constraint equations are singular there",
           lib.PS_ERR_ASSEMBLY: "the position constraints cannot be held"}.get(code)
    return why or describe(model, kernel) or "a value is not finite"


def channels(model, kernel, t, outputs):
    """Log lines for the request channels that are not finite somewhere: one per channel, with
    its expression and the first time (NULL channels, never defined, are left out).

    Parameters
    ----------
    model : Model
    kernel : Kernel
        Its ``channels`` name the columns of `outputs`: (request id, channel index).
    t : ndarray, shape (n,)
    outputs : ndarray, shape (n, len(kernel.channels))
    """
    defined = kernel.defined_channels
    lines = []
    if outputs.size == 0:
        return lines
    # a finite sum: all are finite (a sum that overflows is looked at channel by channel)
    if math.isfinite(np.add.reduce(outputs if len(defined) == outputs.shape[1]
                                   else outputs[:, defined], axis=None)):
        return lines
    bad = ~np.isfinite(outputs)
    for col in defined[bad[:, defined].any(axis=0)]:
        rid, k = kernel.channels[col]
        if rid < 0:                       # a joint's reaction channel (Result.joint), once
            line = (f"Constraint_Joint {-rid} reaction is not finite from t = "
                    f"{t[np.flatnonzero(bad[:, col])[0]]:.6g}")
            if line not in lines:
                lines.append(line)
            continue
        req = model.requests[rid]
        rows = np.flatnonzero(bad[:, col])
        text = req.texts[k] if req.texts[k] else f"{req.usersub.label} channel {k + 1}"
        lines.append(f"request {rid} channel {k + 1} ({text}) is not finite at {len(rows)} of "
                     f"{len(t)} output times, first at t = {t[rows[0]]:.9g} "
                     f"({outputs[rows[0], col]:g})")
    return lines
