"""Per-run overhead and load + compile time (issue 14).

For each seed deck: the time of ``model.run()`` for a zero-length run (the Simulate command
ending at t = 1e-9 s: one tiny step, the fixed cost of a run) and a one-step run (end_time one
print interval), and of the latter ``res.timing["integrate"]`` (IDA, the kernel and the
driver's Python between set-up and the end; the rest is options, set-up and the Result). Then
load + compile, with a cold kernel cache (an empty ``PYSOLVER_CACHE_DIR``: the generated C is
written and compiled) and a warm one (the library is found by its key and loaded), for the seed
decks and the chain of point masses at N = 100, 1000, 5000 (the last two are over
``pysolver.build.codegen.LIMIT`` and run the tapes). Best of several repeats (cold: one).

Run: ``python benchmarks/overhead.py``.
"""
import os
import pathlib
import re
import tempfile
import time

import pysolver

from scenes import chain_deck
from usersubs import best

ROOT = pathlib.Path(__file__).resolve().parent.parent
DECKS = ["particle_between_lines", "particle_above_line", "catenary_bead", "torque_free_spin",
         "spinning_top"]


def one_step_text(text, end=None):
    """The deck with its Simulate command ending after one print interval (or at `end`)."""
    def shorten(m):
        dt = float(re.search(r'print_interval="([^"]+)"', m.group(0)).group(1))
        return re.sub(r'end_time="[^"]+"', f'end_time="{end or dt!r}"', m.group(0))
    return re.sub(r"<Simulate[^>]*>", shorten, text)


def load_times(text, repeat):
    """(cold, warm) seconds of load + compile, and which kernel runs."""
    with tempfile.TemporaryDirectory() as folder:
        os.environ["PYSOLVER_CACHE_DIR"] = folder
        try:
            t0 = time.perf_counter()
            kernel = pysolver.loads(text)._kernel()
            cold = time.perf_counter() - t0
            warm = best(lambda: pysolver.loads(text)._kernel(), repeat)
        finally:
            del os.environ["PYSOLVER_CACHE_DIR"]
    return cold, warm, kernel.codegen


def main():
    print(f"{'deck':>24} {'zero-length us':>14} {'one-step us':>11} {'integrate us':>12} "
          f"{'cold load ms':>12} {'warm load ms':>12} kernel")
    for name in DECKS:
        text = (ROOT / "decks" / f"{name}.xml").read_text()
        cold, warm, info = load_times(text, 20)
        zero = pysolver.loads(one_step_text(text, 1e-9))
        zero.run(progress=False)
        t_zero = best(lambda: zero.run(progress=False), 300)
        model = pysolver.loads(one_step_text(text))
        model.run(progress=False)
        run = best(lambda: model.run(progress=False), 300)
        c_part = min(model.run(progress=False).timing["integrate"] for _ in range(300))
        print(f"{name:>24} {t_zero * 1e6:14.0f} {run * 1e6:11.0f} {c_part * 1e6:12.0f} "
              f"{cold * 1e3:12.1f} {warm * 1e3:12.1f} {info['kernel']}")
    for n in (100, 1000, 5000):
        cold, warm, info = load_times(chain_deck(n), 3 if n < 5000 else 1)
        print(f"{'chain N = ' + str(n):>24} {'':>14} {'':>11} {'':>12} {cold * 1e3:12.1f} "
              f"{warm * 1e3:12.1f} {info['kernel']}")


if __name__ == "__main__":
    main()
