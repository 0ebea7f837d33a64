"""Per-run overhead and load + compile time (issue 14).

For each seed deck: the time of ``model.run()`` for a run with one output step (end_time one
print interval), and of it ``res.timing["integrate"]`` (IDA, the kernel and the driver's
Python between set-up and the end; the rest is options, set-up and the Result); and the time
to load and compile the deck. The
chain of point masses at N = 100, 1000, 5000 for load + compile. Best of several repeats.

Run: ``python benchmarks/overhead.py``.
"""
import pathlib
import re

from usersubs import best

import pysolver

from scenes import chain_deck

ROOT = pathlib.Path(__file__).resolve().parent.parent
DECKS = ["particle_between_lines", "particle_above_line", "catenary_bead", "torque_free_spin",
         "spinning_top"]


def one_step_text(text):
    """The deck with its Simulate command ending after one print interval."""
    def shorten(m):
        dt = float(re.search(r'print_interval="([^"]+)"', m.group(0)).group(1))
        return re.sub(r'end_time="[^"]+"', f'end_time="{dt!r}"', m.group(0))
    return re.sub(r"<Simulate[^>]*>", shorten, text)


def main():
    print(f"{'deck':>24} {'one-step run us':>15} {'integrate us':>12} {'load+compile ms':>15}")
    for name in DECKS:
        text = (ROOT / "decks" / f"{name}.xml").read_text()
        model = pysolver.loads(one_step_text(text))
        model.run(progress=False)
        run = best(lambda: model.run(progress=False), 300)
        c_part = min(model.run(progress=False).timing["integrate"] for _ in range(300))
        load = best(lambda: pysolver.loads(text)._kernel(), 20)
        print(f"{name:>24} {run * 1e6:15.0f} {c_part * 1e6:12.0f} {load * 1e3:15.1f}")
    for n in (100, 1000, 5000):
        text = chain_deck(n)
        load = best(lambda: pysolver.loads(text)._kernel(), 3 if n < 5000 else 1)
        print(f"{'chain N = ' + str(n):>24} {'':>15} {'':>12} {load * 1e3:15.1f}")


if __name__ == "__main__":
    main()
