"""Per-run overhead and load + compile time (issue 14).

For each seed deck: the time of ``model.run()`` for a zero-length run (the Simulate command
ending at t = 1e-9 s: one tiny step, the fixed cost of a run) and a one-step run (end_time one
print interval); for each, ``res.timing["integrate"]`` (IDA and the kernel, in C) and the rest
("outside IDA": Python, plus the initial conditions' few kernel calls), which is the Python a
run costs. Then load + compile, with a cold kernel cache (an empty ``PYSOLVER_CACHE_DIR``: the
generated C is written and compiled) and a warm one (the library is found by its key and
loaded), for the seed decks and the chain of point masses at N = 100, 1000, 5000 (looped C:
see pysolver/build/codegen/looped.py). Best of several repeats (cold: one).

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
            kernel = pysolver.loads(text).compile().kernel
            cold = time.perf_counter() - t0
            warm = best(lambda: pysolver.loads(text).compile().kernel, repeat)
        finally:
            del os.environ["PYSOLVER_CACHE_DIR"]
    return cold, warm, kernel.codegen


def per_run(model, repeat=300):
    """(best total, best time in IDA) of model.run() in seconds."""
    model.run(progress=False)
    total = best(lambda: model.run(progress=False), repeat)
    ida = min(model.run(progress=False).timing["integrate"] for _ in range(repeat))
    return total, ida


def main():
    print(f"{'deck':>24} {'zero-length us':>14} {'outside IDA':>11} {'one-step us':>11} "
          f"{'outside IDA':>11} {'cold load ms':>12} {'warm load ms':>12} kernel")
    for name in DECKS:
        text = (ROOT / "decks" / f"{name}.xml").read_text()
        cold, warm, info = load_times(text, 20)
        zero, zero_ida = per_run(pysolver.loads(one_step_text(text, 1e-9)))
        one, one_ida = per_run(pysolver.loads(one_step_text(text)))
        print(f"{name:>24} {zero * 1e6:14.0f} {(zero - zero_ida) * 1e6:11.0f} {one * 1e6:11.0f} "
              f"{(one - one_ida) * 1e6:11.0f} {cold * 1e3:12.1f} {warm * 1e3:12.1f} "
              f"{info['kernel']}")
    for n in (100, 1000, 5000):
        cold, warm, info = load_times(chain_deck(n), 3 if n < 5000 else 1)
        print(f"{'chain N = ' + str(n):>24} {'':>14} {'':>11} {'':>11} {'':>11} "
              f"{cold * 1e3:12.1f} {warm * 1e3:12.1f} {info['kernel']}")


if __name__ == "__main__":
    main()
