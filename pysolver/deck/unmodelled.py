"""The MotionSolve XML elements outside the schema that a deck may hold: those pysolver does
not model (a DeckError that says so) and those it sets aside (a DeckWarning), and the word
for any other element (unknown, with the closest name pysolver knows).
"""
import difflib

from .schema import SCHEMA

#: MotionSolve elements pysolver does not model: a DeckError saying so (not "unknown"). An
#: element added to SCHEMA leaves this list (tests/test_public_decks.py keeps them apart, and
#: docs/deck-language.md, "Not modelled", lists the same).
NOT_MODELLED = ("Body_Flexible", "Constraint_CVCV", "Constraint_CVSF", "Constraint_Gear",
                "Constraint_PTCV", "Constraint_PTSF", "Constraint_PTdCV", "Constraint_PTdSF",
                "Control_Diff", "Control_SISO", "Control_StateEqn", "Force_Contact",
                "Force_JointFriction", "Force_Scalar_OneBody", "Reference_Array",
                "Reference_Matrix", "Reference_ParamCurve", "Reference_ParamSurface",
                "Reference_String")
#: MotionSolve elements that only name a plant's inputs and outputs (Adams' PINPUT, POUTPUT):
#: read and set aside with a DeckWarning.
SET_ASIDE = ("Control_PlantInput", "Control_PlantOutput")


def not_in_schema(ctx):
    """An element whose tag SCHEMA does not have: one of SET_ASIDE draws a DeckWarning; else a
    DeckError, "not supported" for one of NOT_MODELLED, "unknown" with the closest name
    pysolver knows for any other."""
    tag = ctx.tag
    if tag.lower() in {n.lower() for n in SET_ASIDE}:
        ctx.warn("only names the variables that are a plant's inputs or outputs for "
                 "linearization and control co-simulation; set aside")
        return
    known = {n.lower(): n for n in NOT_MODELLED}
    if tag.lower() in known:
        raise ctx.error(f"<{known[tag.lower()]}> is not supported: a MotionSolve element "
                        "pysolver does not model (docs/deck-language.md, \"Not modelled\")")
    close = difflib.get_close_matches(tag, list(SCHEMA) + list(NOT_MODELLED) + list(SET_ASIDE),
                                      n=1, cutoff=0.75)
    hint = f"; did you mean <{close[0]}>?" if close else ""
    raise ctx.error(f"unknown element <{tag}>{hint} (known elements: "
                    f"{', '.join(sorted(SCHEMA))})")
