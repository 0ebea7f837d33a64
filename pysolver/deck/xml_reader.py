"""MotionSolve XML decks: ``<MotionSolve>`` with ``<Model>`` elements and commands after it.

Reading a deck never executes code: the parser resolves no entities, loads no DTD and
fetches nothing from the network.
"""
from lxml import etree

from ..errors import DeckError

_PARSER = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                          remove_comments=True, remove_pis=True, huge_tree=False)


def read_elements(text, file):
    """Return the deck's elements as (tag, attrs, line, names) in document order."""
    try:
        root = etree.fromstring(text.encode() if isinstance(text, str) else text, _PARSER)
    except etree.XMLSyntaxError as err:
        line = err.lineno if hasattr(err, "lineno") else None
        raise DeckError(f"malformed XML: {err.msg if hasattr(err, 'msg') else err}",
                        file=file, line=line) from None
    elements = []
    model_seen = False
    for child in root:
        if not isinstance(child.tag, str):
            continue
        tag = etree.QName(child).localname
        low = tag.lower()
        if low == "model":
            model_seen = True
            elements.extend(_element(e, file) for e in child if isinstance(e.tag, str))
        elif low == "command":
            elements.extend(_element(e, file) for e in child if isinstance(e.tag, str))
        else:
            elements.append(_element(child, file))
    if not model_seen:
        raise DeckError("no <Model> element: model elements must be inside <Model>", file=file,
                        line=root.sourceline, element=etree.QName(root).localname)
    return elements


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
    return tag, attrs, el.sourceline, names
