"""A deck's elements written as MotionSolve XML (``pysolver convert``), and the element list
every writer starts from.

Every input format is read into the same list of elements (tag, attributes, line, names)
before it is checked, so writing that list as XML translates a Python deck or an Adams
dataset into the XML deck that builds the same model: markers of an .adm deck come out at
their global places (the dataset's part-relative placement resolved), angles in radians.
:func:`typed` gives the same list with each attribute converted to its kind (numbers as
floats, ids as integers, expressions as their text), which the Adams dataset writer
(pysolver/deck/adams_writer.py) and the msolve class script writer (pysolver/convert.py)
write from.
"""
import math
import os

from lxml import etree

from ..errors import DeckError
from .schema import CANONICAL, SCHEMA, SPELLING, Ctx, convert, element_file

#: Elements that are commands: they follow <Model>.
COMMANDS = ("Simulate", "Stop")
#: User subroutine attributes that name a file (relative to the deck's folder).
_PATHS = ("script_name", "usrsub_dll_name")


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


def to_xml(elements, file="<deck>", title=None, out_dir=None):
    """The XML text of a list of deck elements (pysolver.deck.loader's read step).

    Parameters
    ----------
    elements : list of (tag, attrs, line, names)
    file : str
        The deck they were read from (errors name it; user subroutine files are found
        relative to its folder).
    title : str, optional
        A comment at the top.
    out_dir : str, optional
        The folder the XML goes to: user subroutine scripts and libraries given relative to
        the deck's folder are written relative to it.

    Raises
    ------
    DeckError
        An attribute that XML cannot hold: a Python function given as a routine (name it
        in a script instead) or a value that is not finite.
    """
    root = etree.Element("MotionSolve")
    if title:
        while "--" in title:            # an XML comment holds no "--"
            title = title.replace("--", "- -")
        root.append(etree.Comment(f" {title} "))
    model = etree.SubElement(root, "Model")
    for tag, attrs, line, names in elements:
        parent = root if tag in COMMANDS else model
        el = etree.SubElement(parent, tag)
        spelled = SPELLING.get(CANONICAL.get(tag.lower()), {})
        for key, value in attrs.items():
            if value is None:
                continue
            if callable(value):
                raise DeckError("a routine given as a Python function cannot be written to "
                                "XML; give its name and script instead",
                                file=element_file(names, file), line=line,
                                element=tag, attribute=names.get(key, key))
            if key in _PATHS:
                value = relocate(str(value), file, out_dir)
            try:
                text = _text(value)
            except ValueError:
                raise DeckError(f"{value!r} cannot be written to XML",
                                file=element_file(names, file), line=line,
                                element=tag, attribute=names.get(key, key)) from None
            if key == "#text":
                el.text = "\n" + text + "\n"
            else:
                el.set(spelled.get(key, key), text)
    etree.indent(root, space="  ")
    return etree.tostring(root, xml_declaration=True, encoding="utf-8").decode() + "\n"


def relocate(path, deck_file, out_dir):
    """A file a deck names relative to its folder, named relative to `out_dir` (where the
    converted deck goes); other paths as given."""
    if out_dir is None or os.path.isabs(path) or deck_file.startswith("<"):
        return path
    found = os.path.join(os.path.dirname(os.path.abspath(deck_file)), path)
    if not os.path.exists(found):
        return path
    return os.path.relpath(found, os.path.abspath(out_dir))


class Element:
    """One element with its attributes converted to their kinds.

    Attributes
    ----------
    tag : str
        The element's name as the schema spells it (``Body_Rigid``).
    a : dict
        Every attribute of the schema, converted (defaults for those not given);
        expressions are their text, ``usrsub_param_string`` its text.
    given : set of str
        The attributes the deck gave.
    line : int or None
        Its line in the deck.
    raw : dict
        The attributes as read (for elements kept as written: Post_Graphic, ResOutput).
    file : str or None
        The file of its line (the deck's, or an Adams command file's for its commands).
    """

    def __init__(self, tag, a, given, line, raw, file=None):
        self.tag, self.a, self.given, self.line, self.raw = tag, a, given, line, raw
        self.file = file

    def get(self, key):
        """The attribute when the deck gave it, else None."""
        return self.a.get(key) if key in self.given else None


def typed(elements, file):
    """The elements (up to the first Stop: nothing after it is read) as :class:`Element`,
    their attributes converted as the schema says (the deck was loaded, so they convert)."""
    out = []
    for tag, attrs, line, names in elements:
        canon = CANONICAL[tag.lower()]
        given = {k for k, v in attrs.items() if v is not None}
        a = {}
        for key, spec in SCHEMA[canon].items():
            if spec is None:
                continue
            kind, _, default = spec
            if key not in given:
                a[key] = default
            elif kind in ("expr", "expr?"):
                text = str(attrs[key]).strip()
                a[key] = None if kind == "expr?" and text.upper() in ("", "NULL") else text
            elif kind == "user":
                a[key] = str(attrs[key]).strip()
            else:
                a[key] = convert(Ctx(file, canon, attrs, line, names), key, kind, attrs[key])
        out.append(Element(canon, a, {k for k in given if a.get(k) is not None}, line,
                           dict(attrs), element_file(names, file)))
        if canon == "Stop":
            break
    return out
