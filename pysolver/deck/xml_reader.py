"""MotionSolve XML decks: ``<MotionSolve>`` with ``<Model>`` elements and commands after it.

Reading a deck never executes code: the parser resolves no entities, loads no DTD and
fetches nothing from the network.
"""
import re

from lxml import etree

from ..errors import DeckError

_PARSER = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                          remove_comments=True, remove_pis=True, huge_tree=False)


_DECLARED = re.compile(r"""^(\s*<\?xml[^>]*?)\s+encoding\s*=\s*["'][^"']*["']""")


def read_elements(text, file):
    """Return the deck's elements as (tag, attrs, line, names) in document order. Text is
    already decoded: its encoding declaration is dropped (the bytes given to the parser are
    UTF-8)."""
    if isinstance(text, str):
        text = _DECLARED.sub(r"\1", text, count=1).encode()
    try:
        root = etree.fromstring(text, _PARSER)
    except etree.XMLSyntaxError as err:
        line = err.lineno if hasattr(err, "lineno") else None
        raise DeckError(f"malformed XML: {err.msg if hasattr(err, 'msg') else err}",
                        file=file, line=line) from None
    if root.getroottree().docinfo.internalDTD is not None or \
            root.getroottree().docinfo.doctype:
        raise DeckError("a DOCTYPE (DTD, entities) is not allowed in a deck", file=file,
                        line=1)
    elements = []
    model_seen = False
    for child in root:
        if not isinstance(child.tag, str):
            continue
        tag = etree.QName(child).localname
        low = tag.lower()
        if low == "model":
            model_seen = True
            for e in child:
                if not isinstance(e.tag, str):
                    continue
                if etree.QName(e).localname.lower() == "customtasks":
                    elements.extend(_tasks(e, file))
                else:
                    elements.append(_element(e, file))
        elif low == "customtasks":
            elements.extend(_tasks(child, file))
        elif low == "command":
            elements.extend(_element(e, file) for e in child if isinstance(e.tag, str))
        else:
            elements.append(_element(child, file))
    if not model_seen:
        raise DeckError("no <Model> element: model elements must be inside <Model>", file=file,
                        line=root.sourceline, element=etree.QName(root).localname)
    return elements


def _tasks(block, file):
    """<CustomTasks>: each <Schedule name="TASK"> as an element TASK whose attributes are its
    <Parameter name="...">value</Parameter> children (seed 002's layout). A parameter whose
    name holds its value after the first word (``Load_Function 10*t``) gives that value."""
    out = []
    for sched in block:
        if not isinstance(sched.tag, str):
            continue
        if etree.QName(sched).localname.lower() != "schedule":
            raise DeckError("<CustomTasks> holds <Schedule> elements", file=file,
                            line=sched.sourceline, element=etree.QName(sched).localname)
        task = (sched.get("name") or "").strip()
        attrs, names, lines = {}, {}, {}
        for par in sched:
            if not isinstance(par.tag, str):
                continue
            if etree.QName(par).localname.lower() != "parameter" or not par.get("name"):
                raise DeckError("a <Schedule> holds <Parameter name=\"...\"> elements",
                                file=file, line=par.sourceline, element=task or "Schedule")
            key, _, inline = par.get("name").strip().partition(" ")
            low = key.lower()
            if low in attrs:
                raise DeckError("parameter given twice", file=file, line=par.sourceline,
                                element=task, attribute=key)
            attrs[low] = inline.strip() if inline.strip() else (par.text or "").strip()
            names[low] = key
            lines[low] = par.sourceline             # errors in a parameter name its line
        names["#lines"] = lines
        out.append((task or "Schedule", attrs, sched.sourceline, names))
    return out


def _element(el, file):
    tag = etree.QName(el).localname
    if len(el):
        first = next(iter(el))
        raise DeckError(f"<{tag}> must not contain other elements (found <{first.tag}>)",
                        file=file, line=first.sourceline, element=tag)
    attrs, names = {}, {}
    for key, val in el.attrib.items():
        low = etree.QName(key).localname.lower()
        if low in attrs:
            raise DeckError("attribute given twice (names are case-insensitive)", file=file,
                            line=el.sourceline, element=tag, attribute=key)
        attrs[low] = val
        names[low] = etree.QName(key).localname
    for other, key in _SYNONYMS.get(tag.lower(), {}).items():
        if other in attrs:
            if key in attrs:
                raise DeckError(f"give {names[key]} or {names[other]}, not both (the same "
                                "attribute)", file=file, line=el.sourceline, element=tag,
                                attribute=names[other])
            attrs[key], names[key] = attrs.pop(other), names.pop(other)
    if tag.lower() == "reference_spline" and el.text and el.text.strip():
        attrs["#text"], names["#text"] = el.text, "(the element's text)"
    if tag.lower() == "param_unit":
        return _param_unit(attrs, names, el.sourceline, file)
    if tag.lower() in ("body_rigid", "body_point"):
        _ic_flags(attrs, names, el.sourceline, file, tag)
    return tag, attrs, el.sourceline, names


#: Other spellings of attributes in Altair's own examples (docs/deck-language.md): the TIME
#: and TM pages' Motion_Joint writes joint_type, the Simulate page's text num_steps.
_SYNONYMS = {"motion_joint": {"joint_type": "motion_type"},
             "simulate": {"num_steps": "num_step"}}

_TRUE, _FALSE = ("TRUE", "YES", "1", "ON"), ("FALSE", "NO", "0", "OFF")


def _ic_flags(attrs, names, line, file, tag):
    """Body_Rigid's and Body_Point's v_ic_*_flag / w_ic_*_flag (MotionView's
    *SetBodyICFlag: TRUE, the default, uses that initial velocity component, FALSE does not):
    a FALSE flag leaves its component out, as if the deck did not give it (it is then one
    the constraints may set, docs/deck-language.md, "Initial velocities")."""
    spins = "vw" if tag.lower() == "body_rigid" else "v"    # a point body has no w_ic
    for key in [k for k in attrs if re.fullmatch(rf"[{spins}]_ic_[xyz]_flag", k)]:
        value = str(attrs.pop(key)).strip().upper()
        shown = names.pop(key, key)
        if value not in _TRUE + _FALSE:
            raise DeckError(f"got {value!r}; expected TRUE or FALSE", file=file, line=line,
                            element=tag, attribute=shown)
        if value in _FALSE:
            attrs.pop(key[:-5], None)
            names.pop(key[:-5], None)


#: MotionSolve's <Param_Unit> attributes and the <Units> attributes they are.
_PARAM_UNIT = {"mass_unit": "mass", "length_unit": "length", "time_unit": "time",
               "force_unit": "force"}


def _param_unit(attrs, names, line, file):
    """<Param_Unit mass_unit= length_unit= time_unit= force_unit=> (MotionSolve's units
    element, as MotionView writes it) as the <Units> element it is; errors name its own
    attributes. mass_mult_factor, the other form, is refused unless it is 1."""
    factor = attrs.pop("mass_mult_factor", None)
    try:
        one = factor is None or float(factor) == 1.0
    except ValueError:
        one = False
    if not one:
        raise DeckError("mass_mult_factor is not supported: give the units by name "
                        "(mass_unit, length_unit, time_unit, force_unit)", file=file,
                        line=line, element="Param_Unit",
                        attribute=names.get("mass_mult_factor", "mass_mult_factor"))
    out, shown = {}, {"#element": "Param_Unit"}
    for key, value in attrs.items():
        new = _PARAM_UNIT.get(key, key)
        out[new], shown[new] = value, names.get(key, key)
    return "Units", out, line, shown
