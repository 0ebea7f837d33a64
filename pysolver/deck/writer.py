"""A deck's elements written as MotionSolve XML (``pysolver convert``).

Every input format is read into the same list of elements (tag, attributes, line, names)
before it is checked, so writing that list as XML translates a Python deck or an Adams
dataset into the XML deck that builds the same model: markers of an .adm deck come out at
their global places (the dataset's part-relative placement resolved), angles in radians.
"""
import math

from lxml import etree

from ..errors import DeckError

#: Elements that are commands: they follow <Model>.
COMMANDS = ("Simulate", "Stop")


def _text(value):
    """An attribute value as XML text."""
    if isinstance(value, bool):
        return "TRUE" if value else "FALSE"
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(value)
        return repr(value)
    if isinstance(value, (list, tuple)):
        return ", ".join(_text(v) for v in value)
    return str(value)


def to_xml(elements, file="<deck>", title=None):
    """The XML text of a list of deck elements (pysolver.deck.loader's read step).

    Raises
    ------
    DeckError
        An attribute that XML cannot hold: a Python function given as a routine (name it
        in a script instead) or a value that is not finite.
    """
    root = etree.Element("MotionSolve")
    if title:
        root.append(etree.Comment(f" {title.replace('--', '- -')} "))
    model = etree.SubElement(root, "Model")
    for tag, attrs, line, names in elements:
        parent = root if tag in COMMANDS else model
        el = etree.SubElement(parent, tag)
        for key, value in attrs.items():
            if value is None:
                continue
            if callable(value):
                raise DeckError("a routine given as a Python function cannot be written to "
                                "XML; give its name and script instead", file=file, line=line,
                                element=tag, attribute=names.get(key, key))
            try:
                text = _text(value)
            except ValueError:
                raise DeckError(f"{value!r} cannot be written to XML", file=file, line=line,
                                element=tag, attribute=names.get(key, key)) from None
            if key == "#text":
                el.text = "\n" + text + "\n"
            else:
                el.set(key, text)
    etree.indent(root, space="  ")
    return etree.tostring(root, xml_declaration=True, encoding="utf-8").decode() + "\n"
