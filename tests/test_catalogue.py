"""The catalogue of operations and functions (pysolver/catalogue.py) agrees with what cannot
read it: the C enums of csrc/include/pysolver.h and the c_sysfnc tables of csrc/usersub.c, in
both directions and in order; and the documentation's function table is the one it generates."""
import ast
import math
import re

import pytest

from pysolver import catalogue
from pysolver.build.bindings import ffi, lib
from pysolver.build.codegen import sym

from helpers import ROOT, TEST_DECKS

HEADER = (ROOT / "csrc" / "include" / "pysolver.h").read_text()
USERSUB = (ROOT / "csrc" / "usersub.c").read_text()


def _c_code(text):
    """C source without its comments."""
    return re.sub(r"/\*.*?\*/|//[^\n]*", "", text, flags=re.S)


def _enum(name):
    """The enumerators of C enum `name` in pysolver.h, in order, with their values (a value
    may be given for the first only)."""
    body = re.search(r"enum\s+" + name + r"\s*\{(.*?)\}", _c_code(HEADER), re.S).group(1)
    items = [item.strip() for item in body.split(",") if item.strip()]
    names = []
    for k, item in enumerate(items):
        enumerator, _, value = (part.strip() for part in item.partition("="))
        assert not value or (k == 0 and value == "0"), f"{name}: {item} sets its own value"
        names.append(enumerator)
    return names


@pytest.mark.parametrize("enum, prefix, declared", [
    ("psOp", "PS_OP_", catalogue.OPCODES), ("psMeasure", "PS_M_", catalogue.MEASURE_CODES)])
def test_the_c_enums_are_the_catalogues(enum, prefix, declared):
    names = _enum(enum)
    assert names[-1] == f"{prefix}COUNT"
    values = names[:-1]
    assert all(n.startswith(prefix) for n in values)
    missing = set(values) - set(declared)
    assert not missing, f"{enum} values the catalogue does not declare: {sorted(missing)}"
    unknown = set(declared) - set(values)
    assert not unknown, f"catalogue C names {enum} does not have: {sorted(unknown)}"
    assert len(declared) == len(set(declared)) == len(values)
    for k, n in enumerate(names):
        assert getattr(lib, n) == k, f"{n} is {getattr(lib, n)} in the extension, {k} in the header"
    if enum == "psMeasure":     # the kernels read ranges of measures (kind >= PS_M_WX, ...)
        assert list(declared) == values


def test_every_opcode_has_one_record_but_stepc():
    """Each opcode is one record's, but PS_OP_STEPC the STEP family's (one shape each)."""
    owners = {}
    for f in catalogue.TABLE:
        if f.c is not None:
            owners.setdefault(f.c, []).append(f.name)
    shared = {c: names for c, names in owners.items() if len(names) > 1}
    assert shared == {"PS_OP_STEPC": list(catalogue.STEP_SHAPES)}
    assert catalogue.STEP_SHAPES == ("STEP", "STEP5", "HAVSIN")


def _c_strings(pattern, text):
    return re.findall(r'"([^"]*)"', re.search(pattern, text, re.S).group(1))


def test_c_sysfnc_answers_the_catalogues_functions_in_order():
    code = _c_code(USERSUB)
    table = _c_strings(r"FUNCTIONS\[F_COUNT\]\s*=\s*\{(.*?)\};", code)
    assert table == list(catalogue.C_SYSFNC)
    codes = re.search(r"enum\s*\{\s*(F_DX.*?)\}", code, re.S).group(1)
    assert [c.strip() for c in codes.split(",")] == [f"F_{n}" for n in catalogue.C_SYSFNC] + \
        ["F_COUNT"]
    for k, name in enumerate(catalogue.C_SYSFNC):
        assert lib.ps_user_fn_code(name.encode()) == k
    assert lib.ps_user_fn_code(b"MOTION") == -1
    # what c_sysfnc reads, py_sysfnc reads too
    assert set(catalogue.C_SYSFNC) <= {f.name for f in catalogue.TABLE if f.py_sysfnc}


def test_c_sysary_arrays_are_the_catalogues():
    code = _c_code(USERSUB)
    body = re.search(r"ARRAYS\[\]\s*=\s*\{(.*?)\};", code, re.S).group(1)
    arrays = {}
    for name, parts, n in re.findall(r'\{"(\w+)",\s*\{([^}]*)\},\s*(\d+)\}', body):
        arrays[name] = tuple(p.strip()[2:] for p in parts.split(","))
        assert len(arrays[name]) == int(n), name
    assert arrays == catalogue.SYSARY


def test_the_catalogue_reads_no_stage():
    """Records and shared vocabulary: it may import errors, never deck, build or solve."""
    tree = ast.parse((ROOT / "pysolver" / "catalogue.py").read_text())
    internal = {node.module or "" for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)
                and (node.level or (node.module or "").startswith("pysolver"))}
    assert internal <= {"errors", "pysolver.errors"}


def test_records_are_well_formed():
    names = [f.name for f in catalogue.TABLE]
    assert len(names) == len(set(names))
    for f in catalogue.TABLE:
        assert f.kind in catalogue.KINDS, f.name
        assert f.reads <= set(catalogue.READS), f.name
        assert f.doc and "\n" not in f.doc, f.name
        lo, hi = f.arity
        assert 0 <= lo <= hi == len(f.args), f.name
        assert not f.ids or len(f.ids) == len(f.args), f.name
        assert f.math is None or callable(getattr(math, f.math)), f.name
        if f.kind in ("math1", "math2", "arithmetic"):
            assert f.py is not None and f.c is not None, f.name
        if f.kind == "measure":
            assert set(f.args) <= set("ijkl") and f.ids == ("marker",) * hi, f.name
        if f.py_sysfnc or f.c_sysfnc:
            assert f.ids, f.name
    # the generated C knows every one-argument function: a C name and a derivative rule
    math1 = {f.name.lower() for f in catalogue.of_kind("math1")}
    assert set(sym._UNARY) == math1
    assert all(sym.UNARY_C[n] for n in math1)


def test_the_jacobian_deck_uses_every_function():
    """tests/decks/all_functions.xml (test_jacobian.py) calls every function (SENVAL,
    MOTION and JOINT need sensors, motions and joints: test_sensors.py, test_motions.py, and
    all_joints.xml, also in test_jacobian.py, check them; KE, WDTX..WDTZ, WM, ACCM and
    WDTM, which would take
    all_functions.xml past the size generated looped, are in springs.xml's and
    nonholonomic.xml's forces, also in test_jacobian.py, and AXU..AZU, tracked angles, in
    springs.xml's forces, as are SPDP and the splines (LINSPL of TIME: its kinks are not in
    the state); ORIENT, an output whose derivative is singular where a
    parameter passes 0, in springs.xml's request; BUSH, which would remove the bushing the
    bushing tests replace, is compared with the bushing's law in test_bushing.py; FIELD and
    BEAM in field_beam.xml's requests, also in test_jacobian.py; FX..TM, sums of the element
    force functions, are compared with them in test_netforce.py; SHF, POLY, CHEBY, FORCOS and
    FORSIN, written as operations when parsed, are in springs.xml's vector force; JPRIM is
    JOINT once parsed, test_series.py)."""
    text = (TEST_DECKS / "all_functions.xml").read_text().upper()
    used = set(re.findall(r"\b([A-Z][A-Z0-9]*)\s*\(", text))
    assert set(catalogue.FUNCTIONS) - used == {"SENVAL", "MOTION", "JOINT", "KE", "WDTX",
                                                "WDTY", "WDTZ", "ORIENT", "AXU", "AYU",
                                                "AZU", "SPDP", "BUSH", "FIELD", "BEAM",
                                                "AKISPL",
                                                "CUBSPL", "LINSPL", "QUISPL", "FX", "FY",
                                                "FZ", "FM", "TX", "TY", "TZ", "TM", "WM", "ACCM",
                                                "WDTM", "JPRIM", "SHF", "POLY", "CHEBY",
                                                "FORCOS", "FORSIN"}
    assert "JOINT(" in (TEST_DECKS / "all_joints.xml").read_text()
    assert "KE(4)" in (TEST_DECKS / "springs.xml").read_text()
    assert "ORIENT(27" in (TEST_DECKS / "springs.xml").read_text()
    assert all(f"A{c}U(" in (TEST_DECKS / "springs.xml").read_text() for c in "XYZ")
    assert "SPDP(4" in (TEST_DECKS / "springs.xml").read_text()
    assert all(f"{f}(" in (TEST_DECKS / "springs.xml").read_text() for f in
               ("SHF", "POLY", "CHEBY", "FORCOS", "FORSIN"))
    assert all(f"{f}(" in (TEST_DECKS / "springs.xml").read_text() for f in
               ("AKISPL", "CUBSPL", "LINSPL", "QUISPL"))
    assert all(f"WDT{c}(" in (TEST_DECKS / "nonholonomic.xml").read_text() for c in "XYZ")
    assert all(f"{f}(" in (TEST_DECKS / "field_beam.xml").read_text() for f in ("FIELD", "BEAM"))


def test_the_docs_function_table_is_generated():
    page = (ROOT / "docs" / "deck-language.md").read_text()
    assert catalogue.splice(page) == page, \
        "regenerate it: python -m pysolver.catalogue docs/deck-language.md"


def test_element_kinds_match_the_c_diagnosis_the_schema_and_the_statements():
    """Every PS_BAD_* value of an element (csrc/include/pysolver.h) is one catalogue element's,
    every catalogue tag is a schema element, and every statement a pysolver.msolve function."""
    from pysolver.deck import msolve
    from pysolver.deck.schema import SCHEMA
    header = (ROOT / "csrc" / "include" / "pysolver.h").read_text()
    bad = re.search(r"enum \{\s*PS_BAD_NONE = 0,([^}]*)\}", header).group(1)
    element_bads = {n for n in re.findall(r"PS_BAD_\w+", bad)} - {
        "PS_BAD_STATE", "PS_BAD_RATE", "PS_BAD_ELEMENT", "PS_BAD_RESIDUAL", "PS_BAD_JACOBIAN",
        "PS_BAD_DIRECTION"}
    declared = [e.bad for e in catalogue.ELEMENTS if e.bad]
    assert sorted(declared) == sorted(element_bads) and len(set(declared)) == len(declared)
    assert all(isinstance(getattr(lib, name), int) for name in declared)
    for e in catalogue.ELEMENTS:
        assert all(tag in SCHEMA for tag in e.tags), e
        # an element with no deck tag (a tracked angle) is internal and has no statement
        assert (e.statement is None) == (not e.tags), e
        assert e.statement is None or callable(getattr(msolve, e.statement)), e
    assert len({e.kind for e in catalogue.ELEMENTS}) == len({e.table for e in
                                                              catalogue.ELEMENTS}) == \
        len(catalogue.ELEMENTS)


def test_the_element_table_kinds_match_the_c_kinds_and_layouts():
    """The PS_EL_* enum lists the catalogue's table kinds in order, each kind's layout in C
    (ints, value slots, least order) is the catalogue's, and each has its contribution file."""
    header = (ROOT / "csrc" / "include" / "pysolver.h").read_text()
    enum = re.search(r"enum psElement \{([^}]*)\}", header).group(1)
    names = re.findall(r"\b(PS_EL_\w+)", enum)
    assert names == [e.c for e in catalogue.TABLE_KINDS] + ["PS_EL_COUNT"]
    out = [ffi.new("int *") for _ in range(3)]
    for e in catalogue.TABLE_KINDS:
        assert lib.ps_element_layout(getattr(lib, e.c), *out) == lib.PS_OK
        assert [v[0] for v in out] == [len(e.ints), e.values, e.order], e.kind
        roles = [i.split(":")[1] for i in e.ints]
        assert set(roles) <= {"slot", "flag", "marker", "bslot", "state"}, e.kind
        assert roles[:e.values] == ["slot"] * e.values, e.kind
        assert (ROOT / "csrc" / "elements" / f"{e.kind}.c").exists(), e.kind
    assert lib.ps_element_layout(lib.PS_EL_COUNT, *out) == -1
