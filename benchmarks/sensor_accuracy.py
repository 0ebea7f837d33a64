"""Sensor figures: event-time accuracy on exact problems, and what zero crossing buys.

Run: ``python benchmarks/sensor_accuracy.py``. Prints
1. event times against closed forms (free fall through a height, speed threshold, contact
   onset of a ball on a unilateral penalty), with the located-time error;
2. the contact-onset deck with and without zero_crossing: velocity at first contact, the time
   of first contact, the rebound velocity after the whole contact, steps, against a reference
   at integr_tol 1e-11, for six drop heights and two tolerances.
"""
import math
import pathlib

import pysolver

from scenes import G, ball, contact

ROOT = pathlib.Path(__file__).resolve().parent.parent


def event_times():
    print("Event times against closed forms (integr_tol 1e-10 unless noted)")
    print(f"{'case':>44} {'exact':>14} {'located':>18} {'error':>9}")
    cases = [
        ("free fall 10 m -> 5 m (LT)", 'expr="DZ(10)" compare="LT" value="5"', math.sqrt(10 / G)),
        ("free fall 10 m -> 9.9 m (LT)", 'expr="DZ(10)" compare="LT" value="9.9"',
         math.sqrt(0.2 / G)),
        ("speed reaches 5 m/s (GE on VM)", 'expr="VM(10)" compare="GE" value="5"', 5 / G),
    ]
    for name, attrs, exact in cases:
        res = pysolver.loads(ball(f'<Sensor_Event id="1" {attrs} error_tol="1e-9"/>')).run()
        t = res.events[0].time
        print(f"{name:>44} {exact:14.10f} {t:18.14f} {t - exact:9.1e}")
    text = (ROOT / "decks" / "contact_onset_zero_crossing.xml").read_text().replace(
        'integr_tol="1e-3"', 'integr_tol="1e-10"').replace(
        "<Post_Request", '<Sensor_Event id="2" expr="-DZ(10)" compare="GE" value="0" '
        'error_tol="1e-9"/>\n<Post_Request')
    res = pysolver.loads(text).run()
    t = [e.time for e in res.events if e.sensor == 2][0]
    exact = math.sqrt(2 / G)
    print(f"{'contact onset, ball 1 m above a penalty plane':>44} {exact:14.10f} {t:18.14f} "
          f"{t - exact:9.1e}")


def zero_crossing():
    for tol in (1e-3, 1e-5):
        print(f"\nFirst contact with and without zero_crossing = 0.01, integr_tol {tol:g} "
              "(errors against integr_tol 1e-11)")
        print(f"{'drop m':>6} | {'v err plain':>11} {'v err zc':>9} {'ratio':>7} | "
              f"{'t err plain':>11} {'t err zc':>9} | {'rebound dv plain':>16} {'zc':>9} | "
              f"{'steps':>5} {'zc':>5}")
        sums = [0.0, 0.0]
        for z0 in (0.5, 0.8, 1.0, 1.5, 2.0, 3.0):
            t_ref, ref, r_ref = contact(None, z0, integr_tol=1e-11)
            t_p, p, r_p = contact(None, z0, integr_tol=tol)
            t_z, z, r_z = contact(0.01, z0, integr_tol=tol)
            ep, ez = abs(p[1] - ref[1]), abs(z[1] - ref[1])
            sums[0] += ep
            sums[1] += ez
            vend = r_ref.request(1)[-1, 1]
            print(f"{z0:6.1f} | {ep:11.1e} {ez:9.1e} {ep / ez:7.1f} | {t_p - t_ref:11.1e} "
                  f"{t_z - t_ref:9.1e} | {r_p.request(1)[-1, 1] - vend:16.1e} "
                  f"{r_z.request(1)[-1, 1] - vend:9.1e} | {r_p.stats['steps']:5d} "
                  f"{r_z.stats['steps']:5d}")
        print(f"{'sum':>6} | {sums[0]:11.1e} {sums[1]:9.1e} {sums[0] / sums[1]:7.1f}")


if __name__ == "__main__":
    event_times()
    zero_crossing()
