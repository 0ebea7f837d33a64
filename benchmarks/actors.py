"""What a run costs on the batched path against the general loop (issue 27 item 2), in one
process: the sensor decks (every action decided in the batched path's C loop since stop 36,
zero_crossing's restore-and-shrink since stop 37; the general loop acts from Python at each
event, and with zero_crossing at every step), `decks/driven_indenter.xml` (a motion: batched
since stop 36), and the LoadControl decks (updates in the C loop since stop 36; the general loop
calls the same C update from Python at each update time), the particle bed among them (325
states: its restarts on the sparse pattern, in C since stop 37; best of at most 3 runs).

Per deck: the best of REPEAT warm runs on each path (alternated), the steps and the updates, the
time per step and per update, and the ratio general / batched. Both paths give the same rows
to the bit (tests/test_fast.py).

Run: ``python benchmarks/actors.py [--repeat N]``.
"""
import argparse
import pathlib
import time

import pysolver
from pysolver.solve import fast

DECKS = pathlib.Path(__file__).resolve().parents[1] / "decks"
NAMES = ["sensor_halt_acceleration.xml", "sensor_end_condition.xml",
         "sensor_output_interval.xml", "contact_onset_zero_crossing.xml", "driven_indenter.xml",
         "loadcontrol_indenter.xml", "loadcontrol_hertz.xml", "loadcontrol_bed.py"]
#: Decks whose run takes long enough that a few runs give its best.
FEW = {"loadcontrol_bed.py": 3}


def best_of(model, repeat):
    """(best wall seconds of the batched path, of the general loop, the last Result)."""
    times = {True: [], False: []}
    res = None
    for _ in range(repeat):
        for enabled in (True, False):
            fast.ENABLED = enabled
            t0 = time.perf_counter()
            res = model.run(progress=False)
            times[enabled].append(time.perf_counter() - t0)
    fast.ENABLED = True
    return min(times[True]), min(times[False]), res


def main(repeat):
    print(f"{'deck':>32} {'path':>8} {'steps':>6} {'updates':>7} {'run ms':>8} {'us/step':>8} "
          f"{'us/update':>9} {'general/batched':>15}")
    for name in NAMES:
        model = pysolver.load(DECKS / name)
        model.run(progress=False)
        batched, general, res = best_of(model, min(repeat, FEW.get(name, repeat)))
        taken = any(run is not None for _, run in model.compile().batched.values())
        steps = res.stats["steps"]
        updates = sum(len(res.controller(i)["time"]) for i in res._controllers)
        per_update = f"{1e6 * batched / updates:9.1f}" if updates else f"{'':>9}"
        print(f"{name:>32} {'batched' if taken else 'general':>8} {steps:6d} {updates:7d} "
              f"{1e3 * batched:8.3f} {1e6 * batched / steps:8.2f} {per_update} "
              f"{general / batched if taken else 1.0:15.2f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=20)
    main(parser.parse_args().repeat)
