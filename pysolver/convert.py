"""``pysolver convert``: a deck in any format written as MotionSolve XML, as an Adams dataset
(with the command file of its commands) or as a script of msolve classes; the output's
extension chooses.

Every format is read into the same list of elements (pysolver.deck.loader.deck_elements);
pysolver/deck/writer.py writes it as XML, pysolver/deck/adams_writer.py as Adams statements,
and :func:`script` writes those statements as the msolve classes of pysolver/modeling.py
that stand for them (each class's table of keywords, read backwards), so every form builds
the same model, number for number (a marker given by the nine numbers of its axes, which a
dataset gives by REULER, to rounding: docs/adams.md, "Writing datasets").
"""
import ast
import errno
import os

from lxml import etree

from . import modeling
from .deck import adams_writer
from .deck.adams import output_name
from .deck.adams_writer import Function, Ref
from .deck.loader import deck_elements, load
from .deck.writer import to_xml
from .errors import DeckError

#: The output formats, by extension.
FORMATS = {".xml": "MotionSolve XML", ".adm": "an Adams dataset with its command file",
           ".py": "a script of msolve classes"}


def convert(deck, output, user_code=True):
    """Write `deck` in the format of `output`'s extension (.xml, .adm with an .acf of its
    commands beside it, .py a script of msolve classes).

    Parameters
    ----------
    deck : str or os.PathLike
        Any deck pysolver reads (.xml, .py, .adm, .acf).
    output : str or os.PathLike
        The file to write; its folder is made when it does not exist (as ``pysolver run -o``
        makes its output folder).
    user_code : bool, default True
        False refuses a deck that runs code of its own (as :func:`pysolver.load`).

    Returns
    -------
    list of str
        The files written.

    Raises
    ------
    DeckError
        The deck does not load, holds what the format cannot (a routine given as a Python
        function), or the output's extension names no format.
    OSError
        The output's folder cannot be made or a file cannot be written; then nothing new is
        left (an .adm is not written without its .acf, nor a folder made for them).
    """
    texts = forms(deck, output, user_code=user_code)
    folder = os.path.dirname(os.fspath(output))
    if folder and os.path.exists(folder) and not os.path.isdir(folder):
        raise NotADirectoryError(errno.ENOTDIR, "exists and is not a folder", folder)
    made = []                                   # the folders made, deepest first
    while folder and not os.path.exists(folder):
        made.append(folder)
        folder = os.path.dirname(folder)
    if made:
        os.makedirs(made[0])
    try:
        _write_all(texts)
    except BaseException:
        for path in made:
            if not os.listdir(path):
                os.rmdir(path)
        raise
    return list(texts)


def _write_all(texts):
    """Write {path: text} all or nothing: each to a temporary file beside its path, then
    renamed over it once every one is written and no path is a folder; on an error nothing
    new is left (an .adm without its .acf would run with other commands)."""
    temps = {path: os.path.join(os.path.dirname(path),
                                f".{os.path.basename(path)}.{os.getpid()}.tmp")
             for path in texts}
    done = []
    try:
        for path, text in texts.items():
            if os.path.isdir(path):
                raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), path)
            try:
                with open(temps[path], "w", encoding="utf-8") as fh:
                    fh.write(text)
            except OSError as err:          # named by the file asked for, not the temporary
                raise OSError(err.errno, err.strerror, path) from None
        for path in texts:
            existed = os.path.exists(path)
            os.replace(temps[path], path)
            done.append((path, existed))
    except BaseException:
        for path in texts:
            if os.path.exists(temps[path]):
                os.remove(temps[path])
        for path, existed in done:          # a rename that failed after another succeeded
            if not existed:
                os.remove(path)
        raise


def forms(deck, output, user_code=True):
    """{path: text} of the files :func:`convert` writes (the output, and an .adm's .acf)."""
    deck, output = os.fspath(deck), os.fspath(output)
    stem, ext = os.path.splitext(output)
    if ext.lower() not in FORMATS:
        kinds = ", ".join(f"{v} ({k})" for k, v in FORMATS.items())
        raise DeckError(f"unknown output format {ext or '(no extension)'!r}: pysolver convert "
                        f"writes {kinds}", file=output)
    model = load(deck, user_code=user_code)
    elements, _ = deck_elements(deck, user_code=user_code, model=model)
    name = os.path.basename(deck)
    about = description(model.source.text, model.source.fmt)
    out_dir = os.path.dirname(os.path.abspath(output))
    if ext.lower() == ".xml":
        note = f"converted by pysolver from {name}"
        title = note + ("\n" + "\n".join("     " + ln for ln in about.splitlines())
                        if about else "")
        return {output: to_xml(elements, model.source.file, title=title, out_dir=out_dir)}
    dataset, commands = adams_writer.statements(elements, model, model.source.file, out_dir)
    base = os.path.basename(stem)
    # the output name of the deck's command file, else the new file's stem
    kept = output_name(model.source.text) if model.source.fmt == "adm" else None
    if ext.lower() == ".adm":
        title = f"{base}  (converted by pysolver from {name})"
        texts = {output: adams_writer.dataset_text(dataset, title, about)}
        acf = stem + ".acf"
        if commands or os.path.exists(acf):     # an old .acf would give it commands
            texts[acf] = adams_writer.command_text(commands, base, kept)
        return texts
    return {output: script(dataset, commands, kept or base, about, name)}


def description(text, fmt):
    """What a deck says about itself: an XML deck's first comment, a Python deck's
    docstring, an Adams dataset's comment lines after its title (else the title)."""
    if fmt == "xml":
        parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False)
        try:
            root = etree.fromstring(text.encode(), parser)
        except (etree.XMLSyntaxError, ValueError):
            return ""
        nodes = list(reversed(list(root.itersiblings(preceding=True)))) + list(root)
        for node in nodes:
            if isinstance(node, etree._Comment):
                return _dedent(node.text or "")
            if isinstance(node.tag, str):
                break
        return ""
    if fmt == "py":
        try:
            return ast.get_docstring(ast.parse(text)) or ""
        except SyntaxError:
            return ""
    lines = text.splitlines()
    notes = []
    for line in lines[1:]:
        if not line.lstrip().startswith("!"):
            break
        notes.append(line.lstrip()[1:].strip())
    notes = [n for n in notes if "adams_view_name" not in n]
    return "\n".join(notes).strip() or (lines[0].strip() if lines else "")


def _dedent(text):
    lines = [ln.strip() for ln in text.strip().splitlines()]
    return "\n".join(lines)


# ---- the script of msolve classes -------------------------------------------------------
#: The class of each statement.
CLASSES = {cls._statement: cls for cls in (
    modeling.Units, modeling.Accgrav, modeling.Part, modeling.PointMass, modeling.Marker,
    modeling.Joint, modeling.Jprim, modeling.Gcon, modeling.Coupler, modeling.Motion,
    modeling.Sforce, modeling.SpringDamper, modeling.Bushing, modeling.Field,
    modeling.Beam, modeling.Vforce,
    modeling.Vtorque, modeling.Gforce, modeling.Variable, modeling.Spline, modeling.Sensor,
    modeling.SensorEvaluate, modeling.Request, modeling.Graphics, modeling.ResOutput,
    modeling.H3DOutput, modeling.Integrator, modeling.Equilibrium, modeling.Pforce,
    modeling.LoadControl)}
#: A variable's name for the elements others refer to (by the Ref kinds of adams_writer).
_VAR = {"PART": "body", "POINT_MASS": "body", "MARKER": "marker", "JOINT": "joint",
        "JPRIM": "joint", "SENSOR_EVALUATE": "evaluate"}
_SIMULATE = {"DYNAMICS": "DYNAMICS", "KINEMATICS": "KINEMATICS", "STATICS": "STATICS",
             "INITIAL_CONDITIONS": "ASSEMBLY"}
WIDTH = 99


def _attributes(cls):
    """(keyword -> attribute, flag -> (attribute, value)) of a class's table."""
    keys, flags = dict(cls._also), {}
    for attr, spec in cls._keys.items():
        if isinstance(spec, dict):
            for value, flag in spec.items():
                if flag is not None:
                    flags.setdefault(flag, (attr, value))
        else:
            keys.setdefault(spec, attr)
    return keys, flags


def _kwargs(st):
    """[(attribute, value)] of the class call that writes statement `st`."""
    cls = CLASSES[st.name]
    if st.name == "SPLINE":
        return _spline(st)
    keys, flags = _attributes(cls)
    out = []
    for key, value in st.args:
        if value is None and key in flags:
            out.append(flags[key])
        elif value is None and cls is modeling.Graphics:
            out.append(("type", key))           # Adams' shape flag
        elif key in keys:
            out.append((keys[key], True if value is None else value))
        elif cls._any:
            out.append((key.lower(), True if value is None else value))
        else:
            raise AssertionError(f"{st.name}: {key} has no attribute in {cls.__name__}")
    return out


def _spline(st):
    ys = [v for k, v in st.args if k == "Y"]
    out = [("x", dict(st.args)["X"])]
    if len(ys) == 1:
        out.append(("y", ys[0]))
    else:
        out += [("z", [y[0] for y in ys]), ("y", [y[1:] for y in ys])]
    if any(k == "LINEAR_EXTRAPOLATE" for k, _ in st.args):
        out.append(("linear_extrapolate", True))
    return out


def _refs(value):
    values = value if isinstance(value, list) else [value]
    return [v for v in values if isinstance(v, Ref)]


def _source(value):
    """A value as Python source: references by their variables' names."""
    if isinstance(value, Ref):
        return f"{value.kind}{value.id}"
    if isinstance(value, list):
        return "[" + ", ".join(_source(v) for v in value) + "]"
    if isinstance(value, Function):
        return repr(str(value))
    return repr(value)              # numbers with their exact digits, strings quoted


def _call(target, name, args):
    """`target = name(args)` as lines of at most WIDTH columns, arguments aligned."""
    head = f"{target} = {name}(" if target else f"{name}("
    lines, indent = [head], " " * len(head)
    for k, arg in enumerate(args):
        text = arg + ("," if k < len(args) - 1 else ")")
        if len(lines[-1]) + len(text) + (0 if lines[-1].endswith("(") else 1) <= WIDTH or \
                lines[-1].endswith("("):
            lines[-1] += ("" if lines[-1].endswith("(") else " ") + text
        else:
            lines.append(indent + text)
    if not args:
        lines[-1] += ")"
    return lines


def script(dataset, commands, output, about="", source=""):
    """A script of msolve classes that builds the model of the statements (dataset, then the
    commands as model.simulate calls under ``if __name__ == "__main__":``).

    Parameters
    ----------
    dataset, commands : list of adams_writer.Statement
    output : str
        The model's output name.
    about : str
        The deck's description (the script's docstring).
    source : str
        The deck's file name, for the docstring.
    """
    doc = (about + "\n\n" if about else "") + \
        f"pysolver convert wrote this script of msolve classes from {source}:\n" \
        "pysolver.load() reads it, python runs it."
    doc = doc.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
    lines = [f'"""{doc}\n"""', "from pysolver.msolve import *", "",
             f"model = Model(output={output!r})"]
    made, waiting = set(), []
    for st in dataset:
        var = f"{_VAR[st.name]}{st.id}" if st.name in _VAR else None
        args, later = [], []
        for attr, value in _kwargs(st):
            refs = _refs(value)
            if any(f"{r.kind}{r.id}" not in made for r in refs):
                later.append((attr, value))
            else:
                args.append(f"{attr}={_source(value)}")
        if later and var is None:
            var = f"{st.name.lower()}{st.id}"
        if st.id is not None:
            args.insert(0, f"id={st.id}")
        if st.label:
            args.append(f"label={st.label!r}")
        lines += _call(var, CLASSES[st.name].__name__, args)
        if var:
            made.add(var)
        waiting += [(var, attr, value) for attr, value in later]
        # assignments whose references are all made now
        ready = [w for w in waiting if all(f"{r.kind}{r.id}" in made for r in _refs(w[2]))]
        waiting = [w for w in waiting if w not in ready]
        lines += [f"{v}.{attr} = {_source(value)}" for v, attr, value in ready]
    if waiting:
        missing = sorted({f"{r.kind} {r.id}" for _, _, v in waiting for r in _refs(v)
                          if f"{r.kind}{r.id}" not in made})
        raise DeckError(f"the deck refers to {', '.join(missing)}, which it does not define")
    runs = [st for st in commands if st.name == "SIMULATE"]
    if runs:
        lines += ["", 'if __name__ == "__main__":']
        for st in runs:
            kind = next(k for k, v in st.args if v is None)
            args = [f'type="{_SIMULATE[kind]}"'] + \
                [f"{k.lower()}={_source(v)}" for k, v in st.args if v is not None]
            lines += ["    " + ln for ln in _call(None, "model.simulate", args)]
    return "\n".join(lines) + "\n"
