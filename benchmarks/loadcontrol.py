"""LoadControl (seed 002) figures: the load-controlled indenter on a linear floor and on a
Hertz-like contact, with the seed's default gains (Kp 0.1, Ki 0.001) and with Kp = Ki = auto.
Target: ramp to 20 N over 1 s, hold, step to 40 N at t = 2 s; updates every 0.01 s.

Prints, per scene and gains: the ramp's mean lag (t in 0.5..1 s), the error at the end of the
hold (t = 2 s), the step's overshoot (% of the 20 N step), the updates until the load stays
within 2 % of the step, the final A_t and the wall time.

Then the noisy particle bed (decks/loadcontrol_bed.py, load = the contact force): RMS tracking
error after the first 0.2 s, with median_window 1, 5 and 9, for 53 and (with --big) 195
particles.

Run: ``python benchmarks/loadcontrol.py [--big]``.
"""
import pathlib
import time

import numpy as np

import pysolver

DECKS = pathlib.Path(__file__).resolve().parents[1] / "decks"
SEED = {"Kp": "0.1", "Ki": "0.001"}


def with_gains(text, gains):
    for name, value in gains.items():
        text = text.replace(f'<Parameter name="{name}">auto</Parameter>',
                            f'<Parameter name="{name}">{value}</Parameter>')
    return text


def figures(res):
    c = res.controller(1)
    t, load, target = c["time"], c["measured"], c["target"]
    err = load - target
    ramp = (t > 0.5) & (t <= 1.0)
    step = t >= 2.0
    outside = np.nonzero(np.abs(load[step] - 40.0) > 0.02 * 20.0)[0]
    settle = outside[-1] + 1 if len(outside) else 0
    settle = f"{settle}" if settle < step.sum() else f">{step.sum()}"
    hold_end = err[np.searchsorted(t, 2.0) - 1]
    return (np.mean(-err[ramp]), hold_end, 100 * (load[step].max() - 40.0) / 20.0, settle,
            c["A"][-1])


def bed(sizes):
    print(f"\n{'particles':>9} {'median':>6} {'RMS error N':>11} {'kurtosis':>8} {'clamped':>7} "
          f"{'s':>6}")
    text = (DECKS / "loadcontrol_bed.py").read_text()
    for nx, nz in sizes:
        for window in (1, 5, 9):
            deck = text.replace("MEDIAN_WINDOW = 1", f"MEDIAN_WINDOW = {window}").replace(
                "NX, NZ = 11, 5", f"NX, NZ = {nx}, {nz}")
            t0 = time.perf_counter()
            res = pysolver.loads(deck, fmt="py").run()
            sec = time.perf_counter() - t0
            c = res.controller(1)
            late = c["time"] > 0.2
            rms = np.sqrt(np.mean((c["measured"][late] - c["target"][late]) ** 2))
            d = np.diff(c["measured"])
            kurt = np.mean((d - d.mean()) ** 4) / np.var(d) ** 2
            particles = nx * nz - nz // 2          # odd rows hold one particle fewer
            print(f"{particles:9d} {window:6d} {rms:11.4f} {kurt:8.1f} {int(c['clamped'].sum()):7d} "
                  f"{sec:6.1f}")


def main():
    print(f"{'scene':>9} {'gains':>6} {'ramp lag N':>10} {'hold err N':>10} {'overshoot %':>11} "
          f"{'settle upd':>10} {'A_t end':>9} {'ms':>6}")
    for scene in ("indenter", "hertz"):
        text = (DECKS / f"loadcontrol_{scene}.xml").read_text()
        for label, gains in (("seed", SEED), ("auto", {})):
            model = pysolver.loads(with_gains(text, gains))
            model.run()
            t0 = time.perf_counter()
            res = model.run()
            ms = 1e3 * (time.perf_counter() - t0)
            lag, hold, over, settle, A = figures(res)
            print(f"{scene:>9} {label:>6} {lag:10.3f} {hold:10.3f} {over:11.2f} {settle:>10} "
                  f"{A:9.2f} {ms:6.0f}")


if __name__ == "__main__":
    import sys
    main()
    bed([(11, 5)] + ([(20, 10)] if "--big" in sys.argv else []))
