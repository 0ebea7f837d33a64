"""The documentation stays true: every deck it names exists and runs, its links resolve, and
the README's Python example runs as written."""
import os
import re

import pytest

import pysolver

from helpers import ROOT

PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))


def _named_decks():
    """Deck paths the pages name, with ``name.{xml,py}`` expanded."""
    found = set()
    for page in PAGES:
        for stem, exts in re.findall(r"(?<![\w/])decks/([\w-]+)\.(\{[\w,]+\}|xml|py)(?!\w)",
                                     page.read_text()):
            for ext in exts.strip("{}").split(","):
                found.add(f"decks/{stem}.{ext}")
    return sorted(found)


def test_the_docs_list_every_deck():
    shipped = {f"decks/{p.name}" for p in (ROOT / "decks").iterdir() if p.suffix in (".xml", ".py")}
    assert set(_named_decks()) == shipped


@pytest.mark.parametrize("name", _named_decks())
def test_every_deck_the_docs_name_runs(name):
    path = ROOT / name
    assert path.exists(), f"{name} is named in the docs but does not exist"
    res = pysolver.load(path).run(progress=False)
    assert res.success, res.message
    assert len(res.t) >= 2 and res.t[-1] > res.t[0] or res.statics


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_links_resolve(page):
    for target in re.findall(r"\]\(([^)#:]+)\)", page.read_text()):
        assert (page.parent / target).exists(), f"{page.name} links to missing {target}"


def test_readme_python_example_runs(capsys):
    text = (ROOT / "README.md").read_text()
    (example,) = re.findall(r"## From Python\n\n```python\n(.*?)```", text, flags=re.S)
    assert len(example.strip().splitlines()) <= 12
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        exec(compile(example, "README.md", "exec"), {})
    finally:
        os.chdir(cwd)
    out = capsys.readouterr().out
    assert "success: True" in out
