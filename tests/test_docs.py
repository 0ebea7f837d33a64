"""The documentation stays true: every deck it names exists and runs, its links resolve, and
the README's Python and user subroutine examples run as written."""
import os
import pathlib
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


def test_readme_user_subroutine_examples_run(tmp_path):
    """The README's XML element, Python script, C source and build command, as written, give
    seed example 1's answers (traced Python: the expression's; C, which takes its own steps:
    within 1e-7, relative for the force, at integr_tol 1e-10)."""
    import shutil
    import subprocess
    import sys

    import numpy as np
    text = (ROOT / "README.md").read_text().split("## User subroutines", 1)[1]
    (element,) = re.findall(r"```xml\n(.*?)```", text.split("##")[0], flags=re.S)
    script = re.search(r"```python\n# bead.py\n(.*?)```", text, flags=re.S).group(1)
    source = re.search(r"```c\n/\* bead.c \*/\n(.*?)```", text, flags=re.S).group(1)
    build = re.search(r"```bash\n(cc -shared .*?)\n```", text, flags=re.S).group(1)
    (tmp_path / "bead.py").write_text(script)
    deck = re.sub(r"<Force_Penalty .*?/>", element.strip(),
                  (ROOT / "decks" / "catenary_bead.xml").read_text(), flags=re.S)
    (tmp_path / "bead.xml").write_text(deck)
    ref = pysolver.load(ROOT / "decks" / "catenary_bead.xml").run(integr_tol=1e-10)
    res = pysolver.load(tmp_path / "bead.xml").run(integr_tol=1e-10)
    assert res.success and "traced into the kernel" in str(res.meta["usersubs"])
    np.testing.assert_allclose(res.request(1)[:, :6], ref.request(1)[:, :6], rtol=0, atol=1e-9)
    if shutil.which("cc") is None:
        pytest.skip("no C compiler (cc) on this machine to build the README's library")
    (tmp_path / "bead.c").write_text(source)
    # the pysolver this test imports, installed or not
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(pysolver.__file__).parents[1]))
    subprocess.run(build.replace("python -c", f"{sys.executable} -c"), shell=True,
                   cwd=tmp_path, check=True, env=env)
    (tmp_path / "bead_c.xml").write_text(deck.replace('script_name="bead.py"',
                                                      'usrsub_dll_name="bead.so"'))
    res = pysolver.load(tmp_path / "bead_c.xml").run(integr_tol=1e-10)
    assert res.success and "C library" in str(res.meta["usersubs"])
    np.testing.assert_allclose(res.request(1)[:, :6], ref.request(1)[:, :6], rtol=1e-7, atol=1e-7)


def test_readme_batch_example_runs(tmp_path):
    """The README's sweep example, as a plain script (no main guard: workers never import
    it), in a fresh folder: every case ok, the directory written."""
    import subprocess
    import sys
    text = (ROOT / "README.md").read_text().split("## Batch studies", 1)[1]
    script = re.search(r"```python\n(.*?)```", text, flags=re.S).group(1)
    script = script.replace('"decks/', f'"{ROOT}/decks/')
    script += 'assert (sw.table["status"] == "ok").all() and res.success\n'
    (tmp_path / "study.py").write_text(script)
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(pysolver.__file__).parents[1]))
    out = subprocess.run([sys.executable, "study.py"], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert len(list((tmp_path / "study" / "results").glob("*.pkl"))) == 12


def test_readme_python_example_runs_from_a_checkout_root(tmp_path):
    """Issue 13: after the README's install, the example run from the repository root imported
    the checkout's own ``pysolver`` folder (it shadows the installed package), whose kernel was
    not built: "C kernel is not built". Now a checkout builds its kernel in place on first
    import. Checked on a copy of the source tree without any built kernel, as `python -c`
    from its root."""
    import shutil
    import subprocess
    import sys
    files = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True)
    if files.returncode:
        pytest.skip("not a git checkout")
    copy = tmp_path / "checkout"
    for name in files.stdout.splitlines():
        if name.startswith(("pysolver/", "csrc/", "decks/")):
            (copy / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, copy / name)
    assert not list((copy / "pysolver").glob("_kernel*"))
    text = (ROOT / "README.md").read_text()
    (example,) = re.findall(r"## From Python\n\n```python\n(.*?)```", text, flags=re.S)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    out = subprocess.run([sys.executable, "-c", example], cwd=copy, env=env,
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    assert "success: True" in out.stdout
    assert "building the C kernel in this source checkout" in out.stderr
    assert list((copy / "pysolver").glob("_kernel*"))
