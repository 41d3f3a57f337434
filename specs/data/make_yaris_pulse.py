"""Writes yaris_pulse.csv: the deceleration pulse of the paper's scenario with
a 10 % stiffer front end (every crush stiffness value times 1.1), as a
target for `lpm fit` in the README (the fit should find k1...k6 times 1.1).

Made from the trajectory of

    lpm simulate specs/yaris_double_pendulum.lpm --out /tmp/stiffer \
        --set 'components.front_end.stiffness_values=[2.64e6, 2.64e6, 2.31e6, 1.034e6, 0.6237e6, 0.55e6, 0.61875e6]'

then `python3 specs/data/make_yaris_pulse.py /tmp/stiffer/trajectory.csv`:
the deceleration r'' in g (9.80665 m/s^2; the crush is -r, so the
deceleration towards the barrier is +r'') every 0.5 ms up to 100 ms.
"""

import csv
import sys

G = 9.80665


def main(trajectory, out="specs/data/yaris_pulse.csv"):
    with open(trajectory) as f:
        rows = list(csv.DictReader(f))
    column = next(name for name in rows[0] if name.startswith("r_ddot"))
    with open(out, "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(["t [ms]", "deceleration [g]"])
        for k, row in enumerate(rows):
            t = float(row["t [s]"])
            if t > 0.1 + 1e-9:
                break
            if k % 5 == 0:  # 0.1 ms samples -> 0.5 ms
                writer.writerow([f"{t * 1e3:.1f}", f"{float(row[column]) / G:.6f}"])


if __name__ == "__main__":
    main(*sys.argv[1:])
