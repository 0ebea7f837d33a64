"""Writes every example deck's other forms with pysolver convert: the Adams dataset and its
command file (decks/forms/adams/NAME.adm, .acf) and the script of msolve classes
(decks/forms/msolve/NAME.py), for decks/*.xml, decks/*.py and decks/joints/*.xml (joints/
forms under adams/joints/ and msolve/joints/). A deck written both as XML and as Python
statements (catenary_bead.xml and .py, ...) has one set of forms, from the XML: both build
the same model. tests/test_formats.py fails when a form here is out of date with what
convert writes, and runs every form of every deck.

    python decks/forms/make.py
"""
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
DECKS = HERE.parent


def sources():
    """The example decks, each with its forms' folder (decks/ or decks/joints/)."""
    xml = sorted(DECKS.glob("*.xml"))
    python = [p for p in sorted(DECKS.glob("*.py")) if not p.with_suffix(".xml").exists()]
    return [(p, "") for p in xml + python] + \
        [(p, "joints") for p in sorted((DECKS / "joints").glob("*.xml"))]


def outputs(deck, sub):
    """The dataset and the class script a deck's forms go to."""
    return (HERE / "adams" / sub / f"{deck.stem}.adm",
            HERE / "msolve" / sub / f"{deck.stem}.py")


def all_forms():
    """{path: text} of every form of every example deck."""
    from pysolver.convert import forms
    out = {}
    for deck, sub in sources():
        for target in outputs(deck, sub):
            out.update({pathlib.Path(p): text for p, text in forms(deck, target).items()})
    return out


if __name__ == "__main__":
    sys.path.insert(0, str(DECKS.parent))      # this checkout's pysolver
    for path, text in all_forms().items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        print(f"wrote {path.relative_to(DECKS.parent)}")
