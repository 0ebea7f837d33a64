"""A seeded deck fuzzer: mutated XML and Python decks and random expressions, each loaded and run
in a worker subprocess with a timeout.

Acceptable outcomes: a DeckError; ``success=False`` with a message (a run stopped by the
timeout's SIGINT must come back as such, status -600); success with finite times and states
and every non-finite request channel listed in ``res.log``. Anything else is a defect: another
exception (a traceback into internals), a crash (the worker died), a hang (no answer 5 s after
SIGINT), or success with non-finite results.

``python tests/fuzz.py --cases 10000`` runs a long campaign and prints the counts; the test
suite runs a fast subset (``tests/test_fuzz.py``; ``pytest --fuzz-cases N`` for more).
"""
import argparse
import collections
import json
import os
import pathlib
import random
import re
import select
import signal
import subprocess
import sys
import threading

ROOT = pathlib.Path(__file__).resolve().parents[1]
SEEDS = sorted(p for p in (ROOT / "decks").iterdir()
               if p.suffix in (".xml", ".py") and p.stem not in ("loadcontrol_bed",
                                                                 "catenary_bead"))
GOOD = {"deck_error", "failed", "success"}

FUNCS1 = ["ABS", "ACOS", "ASIN", "ATAN", "COS", "COSH", "SIN", "SINH", "TAN", "TANH", "EXP",
          "LOG", "LOG10", "SQRT", "AINT", "ANINT"]
FUNCS2 = ["ATAN2", "MOD", "MAX", "MIN", "SIGN", "DIM"]
MEASURES = ["DX", "DY", "DZ", "DM", "VX", "VY", "VZ", "VM", "VR", "WX", "WY", "WZ", "ACCX",
            "ACCY", "ACCZ", "AX", "AY", "AZ"]
NUMBERS = ["0", "1", "-1", "2.5", "1e3", "1E-9", "1D2", "1e308", "1e-308", ".5", "3.", "1e999",
           "PI", "TIME", "DTOR"]
VALUES = ["", " ", "0", "-0", "1", "-1", "2", "0.5", "1e999", "-1e999", "nan", "NaN", "inf",
          "-inf", "1e308", "1e-300", "1e-320", "99999999999999999999", "2147483648", "-2147483649",
          "abc", "TRUE", "FALSE", "yes", "3.5.1", "1,2", "0x10", "1e", "e5", "--1", "1 2",
          "\u00e9", "\u00a0", "NULL", "Force", "EXPRESSION", "USER(1,2)", "X", "B1", "D", "GE",
          "STATIC", "TRANSIENT", "QUASI-STATIC"]
ATTACKS = [
    '<?xml version="1.0"?>\n<!DOCTYPE lolz [<!ENTITY lol "lol"><!ENTITY lol2 '
    '"&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">]>\n<MotionSolve>&lol2;</MotionSolve>',
    '<?xml version="1.0"?>\n<!DOCTYPE x [<!ENTITY e SYSTEM "file:///etc/passwd">]>\n'
    '<MotionSolve><Model>&e;</Model></MotionSolve>',
    '<?xml version="1.0" encoding="UTF-16"?>\n<MotionSolve/>',
    '<?xml version="1.0" encoding="bogus"?>\n<MotionSolve/>',
    '<MotionSolve>' * 5000,
    '',
    '\x00\x01\x02',
]


def random_expr(rng, depth=0):
    """A random expression of the deck language (some of them invalid on purpose)."""
    r = rng.random()
    if depth > 4 or r < 0.25:
        return rng.choice(NUMBERS + [f"{rng.uniform(-10, 10):.3g}"])
    if r < 0.45:
        ids = [rng.choice(["10", "11", "20", "21", "1", "2", "0", "999", "-3"])
               for _ in range(rng.randint(0, 4))]
        return f"{rng.choice(MEASURES)}({','.join(ids)})"
    if r < 0.6:
        return f"{rng.choice(FUNCS1)}({random_expr(rng, depth + 1)})"
    if r < 0.7:
        return f"{rng.choice(FUNCS2)}({random_expr(rng, depth + 1)},{random_expr(rng, depth + 1)})"
    if r < 0.8:
        args = [random_expr(rng, depth + 1) for _ in range(5)]
        return f"{rng.choice(['STEP', 'STEP5', 'HAVSIN'])}({','.join(args)})"
    if r < 0.85:
        a, b, c, d = (random_expr(rng, depth + 1) for _ in range(4))
        return f"IF({a}:{b},{c},{d})"
    if r < 0.9:
        return f"{rng.choice(['VARVAL', 'PFORCE', 'SENVAL'])}({rng.choice(['1', '10', '999'])})"
    op = rng.choice(["+", "-", "*", "/", "**", "", ",", "(("])
    return f"({random_expr(rng, depth + 1)} {op} {random_expr(rng, depth + 1)})"


_ATTR = re.compile(rb'(\s)([A-Za-z_0-9]+)="([^"]*)"')
_ELEMENT = re.compile(rb"^\s*<[A-Za-z_]+[^\n]*(?:\n[^<\n]*)*?/>\s*$", re.M)
_PY_NUMBER = re.compile(rb"(?<![A-Za-z_0-9.])\d+\.?\d*(?:[eE][+-]?\d+)?")
_PY_STRING = re.compile(rb'"[^"\n]*"')


def mutate(raw, fmt, rng):
    """Return (mutated bytes, what was done)."""
    kind = rng.choice(["value", "value", "expr", "expr", "drop_attr", "drop_element",
                       "dup_element", "truncate", "bytes", "attack", "ids", "many"])
    if kind == "attack" and fmt == "xml":
        return rng.choice(ATTACKS).encode("utf-8", "surrogatepass"), kind
    if kind == "truncate":
        return raw[:rng.randrange(len(raw) + 1)], kind
    if kind == "bytes":
        pos = rng.randrange(len(raw) + 1)
        junk = bytes(rng.randrange(256) for _ in range(rng.randint(1, 8)))
        return raw[:pos] + junk + raw[pos:], kind
    if kind == "many":
        for _ in range(rng.randint(2, 5)):
            raw, _ = mutate(raw, fmt, rng)
        return raw, kind
    if fmt == "py":
        return _mutate_python(raw, kind, rng), kind
    attrs = list(_ATTR.finditer(raw))
    if kind in ("value", "expr", "ids", "drop_attr") and attrs:
        if kind == "expr":
            exprs = [m for m in attrs if m.group(2).lower().startswith((b"expr", b"load_fun"))]
            attrs = exprs or attrs
        m = rng.choice(attrs)
        if kind == "drop_attr":
            return raw[:m.start()] + raw[m.end():], kind
        if kind == "expr":
            new = random_expr(rng)
        elif kind == "ids":
            new = rng.choice(["0", "1", "2", "10", "20", "999", "-1"])
        else:
            new = rng.choice(VALUES)
        new = new.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;")
        return raw[:m.start(3)] + new.encode() + raw[m.end(3):], kind
    elements = list(_ELEMENT.finditer(raw))
    if elements:
        m = rng.choice(elements)
        if kind == "dup_element":
            return raw[:m.end()] + b"\n" + m.group(0) + raw[m.end():], kind
        return raw[:m.start()] + raw[m.end():], kind
    return raw, kind


def _mutate_python(raw, kind, rng):
    if kind in ("expr", "ids") and _PY_STRING.search(raw):
        m = rng.choice(list(_PY_STRING.finditer(raw)))
        return raw[:m.start()] + f'"{random_expr(rng)}"'.encode() + raw[m.end():]
    numbers = list(_PY_NUMBER.finditer(raw))
    if kind in ("value", "ids", "expr") and numbers:
        m = rng.choice(numbers)
        new = rng.choice(["0", "-1", "1e999", "1e308", "1e-300", "2", "99999999999", "0.0",
                          "float('nan')", "None", "'x'", "[]", "-0.0", "3"])
        return raw[:m.start()] + new.encode() + raw[m.end():]
    lines = raw.split(b"\n")
    i = rng.randrange(len(lines))
    if kind == "dup_element":
        lines.insert(i, lines[i])
    else:
        del lines[i]
    return b"\n".join(lines)


def cases(n, seed=0):
    """n fuzz cases: (index, suffix, bytes, what) from one seeded generator."""
    rng = random.Random(seed)
    texts = [(p.suffix, p.read_bytes()) for p in SEEDS]
    for i in range(n):
        suffix, raw = rng.choice(texts)
        if rng.random() < 0.1:              # a valid deck with one random expression
            raw = raw.replace(b'expr="', f'expr="{random_expr(rng)} + '.replace(
                "&", "&amp;").replace("<", "&lt;").encode(), 1) if suffix == ".xml" else raw
            yield i, suffix, raw, "random_expr"
            continue
        mutated, what = mutate(raw, suffix[1:], rng)
        yield i, suffix, mutated, what


WORKER = r"""
import json, math, os, sys, traceback
import numpy as np
import pysolver
os.chdir(sys.argv[1])
# answers go to a private copy of stdout: a deck that prints writes to stderr instead
answers = os.fdopen(os.dup(1), "w")
os.dup2(2, 1)
sys.stdout = sys.stderr
for line in sys.stdin:
    path = json.loads(line)["path"]
    try:
        try:
            model = pysolver.load(path)
            res = model.run(progress=False)
        except pysolver.DeckError as err:
            out = {"outcome": "deck_error", "message": str(err)[:300]}
        else:
            if not res.success:
                ok = bool(res.message)
                out = {"outcome": "failed" if ok else "no_message", "status": res.status,
                       "message": res.message[:300]}
            else:
                finite = all(np.isfinite(a).all() for a in (res.t, res.y, res.yp))
                bad_cols = [(rid, k) for rid, req in model.requests.items() for k in range(8)
                            if (req.exprs[k] is not None or req.usersub is not None)
                            and not np.isfinite(res.request(rid)[:, k]).all()]
                logged = len([l for l in res.log if "is not finite" in l]) >= len(bad_cols)
                out = {"outcome": "success" if finite and logged else "nonfinite",
                       "status": res.status, "bad_channels": bad_cols[:5]}
    except KeyboardInterrupt:
        out = {"outcome": "failed", "status": "interrupted in Python",
               "message": "KeyboardInterrupt"}
    except BaseException as err:
        out = {"outcome": "traceback", "message": traceback.format_exc()[-2000:]}
    print(json.dumps(out), file=answers, flush=True)
"""


def _package_parent():
    """The folder holding the pysolver this process imports (installed or the checkout), so
    that workers test the same one and never build a kernel of their own."""
    try:
        import pysolver
    except ImportError:
        return ROOT
    return pathlib.Path(pysolver.__file__).resolve().parents[1]


class Worker:
    """A Python process loading and running decks one at a time (restarted after a crash or a
    hang)."""

    def __init__(self, folder):
        self.folder = folder
        self.proc = None

    def _start(self):
        env = dict(os.environ, PYTHONPATH=str(_package_parent()), OMP_NUM_THREADS="1",
                   OPENBLAS_NUM_THREADS="1", PYSOLVER_OUTPUT_BUDGET=str(2 ** 29))
        # run in the cases' folder: `python -c` puts its working folder first on the path,
        # and a checkout there would shadow the package under test
        self.proc = subprocess.Popen([sys.executable, "-c", WORKER, self.folder],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL, text=True, env=env,
                                     cwd=self.folder)

    def _read(self, timeout):
        ready, _, _ = select.select([self.proc.stdout], [], [], timeout)
        if not ready:
            return None
        line = self.proc.stdout.readline()
        if not line:
            return {"outcome": "crash", "status": self.proc.wait()}
        try:
            return json.loads(line)
        except ValueError:
            return {"outcome": "garbled", "line": line[:300]}

    def run(self, path, timeout):
        if self.proc is None or self.proc.poll() is not None:
            self._start()
        self.proc.stdin.write(json.dumps({"path": path}) + "\n")
        self.proc.stdin.flush()
        out = self._read(timeout)
        if out is None:                       # too long: Ctrl-C must stop it cleanly
            self.proc.send_signal(signal.SIGINT)
            out = self._read(5.0)
            if out is None:
                self.proc.kill()
                self.proc.wait()
                return {"outcome": "hang"}
            out["timed_out"] = True
        if out["outcome"] == "crash":
            self.proc = None
        return out

    def close(self):
        if self.proc is not None and self.proc.poll() is None:
            self.proc.stdin.close()
            self.proc.wait()


def campaign(n, folder, seed=0, workers=2, timeout=10.0):
    """Run n cases; returns (Counter of outcomes, list of bad cases with their decks)."""
    todo = list(cases(n, seed))
    counts, bad = collections.Counter(), []
    lock = threading.Lock()

    def work(k):
        w = Worker(folder)
        try:
            for i, suffix, raw, what in todo[k::workers]:
                path = os.path.join(folder, f"case{i}{suffix}")
                with open(path, "wb") as fh:
                    fh.write(raw)
                out = w.run(path, timeout)
                with lock:
                    counts[out["outcome"]] += 1
                    counts[f"what:{what}"] += 1
                    if out.get("timed_out"):
                        counts["timed out, then interrupted"] += 1
                    if out["outcome"] not in GOOD:
                        bad.append((i, what, out, raw[:4000]))
                os.remove(path)
        finally:
            w.close()

    threads = [threading.Thread(target=work, args=(k,)) for k in range(workers)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    return counts, bad


def main():
    import tempfile
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--cases", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=10.0)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        counts, bad = campaign(args.cases, folder, args.seed, args.workers, args.timeout)
    print(json.dumps(dict(sorted(counts.items())), indent=1))
    for i, what, out, raw in bad[:20]:
        print(f"--- case {i} ({what}): {json.dumps(out)[:1500]}\n{raw[:600]!r}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
