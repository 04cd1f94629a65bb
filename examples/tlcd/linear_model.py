#!/usr/bin/python3
"""The linear TLCD model of the tuning study (README.md, "The tuning study"): Sakai's equations
for a structure of one degree of freedom with a liquid column on it,

  (M + m) x'' + alpha m u'' + c_s x' + k x = 0
  m u''  + alpha m x'' + c_d u' + m w_d^2 u = 0

x the building's tip, u the column's displacement along the tube, m = rho_w (2 b (fill - b) +
(D + b) b) the water, alpha = D / L, w_d = 2 pi / T_d the column's circular frequency (linear
theory's sqrt(2 g / L) raised by `--column-speedup`, 1.8 % for our d = 5 mm U-tube), c_d =
2 zeta_d w_d m (--column-damping, our U-tube's 0.06-0.10), M the building's modal mass without
the water, k from the building's period with the water lumped (the tuning study's --mbd-only
runs, lumped.csv or the defaults below), c_s for a 1.2 % damping. Released from x = 15 mm at rest,
it is integrated exactly (matrix exponential) and measured as analyze.py measures the runs: the
logarithmic decrement over the first four periods of the positive extrema of x.

  linear_model.py [--column-damping 0.06,0.10] [--column-speedup 0.018]"""
import argparse
import math

import numpy as np

G = 9.81
B = 0.04
D = 0.30
MODAL_MASS = 230.0 + 0.236 * 2.0 * 20.0   # top storey + the cantilever's modal share of its 40 kg/m
# The building's period with each fill's water lumped on its top (tuning.py's --mbd-only runs).
LUMPED_PERIOD = {0.08: 1.0038, 0.11: 1.0088, 0.14: 1.0150, 0.17: 1.0200, 0.20: 1.0250}


def decrement_damping(fill, zeta_d, speedup, cycles=4):
    length = 2 * (fill - B / 2) + D
    water = 1000.0 * (2 * B * (fill - B) + (D + B) * B)
    alpha = D / length
    w_d = math.sqrt(2 * G / length) * (1 + speedup)
    k = (MODAL_MASS + water) * (2 * math.pi / LUMPED_PERIOD[fill]) ** 2
    c_s = 2 * 0.012 * math.sqrt(k * (MODAL_MASS + water))
    mass = np.array([[MODAL_MASS + water, alpha * water], [alpha * water, water]])
    damping = np.diag([c_s, 2 * zeta_d * w_d * water])
    stiffness = np.diag([k, water * w_d ** 2])
    inverse = np.linalg.inv(mass)
    system = np.block([[np.zeros((2, 2)), np.eye(2)], [-inverse @ stiffness, -inverse @ damping]])
    values, vectors = np.linalg.eig(system)
    start = np.linalg.solve(vectors, np.array([0.015, 0.0, 0.0, 0.0]))
    times = np.arange(0.0, 8.0, 1e-3)
    x = np.array([(vectors[0] * np.exp(values * t) * start).sum().real for t in times])
    peaks = [x[0]] + [x[i] for i in range(1, len(x) - 1) if x[i] > 0 and x[i - 1] < x[i] >= x[i + 1]]
    delta = math.log(peaks[0] / peaks[cycles]) / cycles
    return delta / math.sqrt(4 * math.pi ** 2 + delta ** 2), w_d * LUMPED_PERIOD[fill] / (2 * math.pi)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--column-damping", default="0.06,0.10")
    parser.add_argument("--column-speedup", type=float, default=0.018)
    args = parser.parse_args()
    dampings = [float(v) for v in args.column_damping.split(",")]
    print("fill [m]  frequency ratio  " + "  ".join(f"zeta (column {z:g})" for z in dampings))
    for fill in sorted(LUMPED_PERIOD):
        results = [decrement_damping(fill, z, args.column_speedup) for z in dampings]
        print(f"{fill:7.2f}  {results[0][1]:15.3f}  " + "  ".join(f"{r[0]:18.4f}" for r in results))


if __name__ == "__main__":
    main()
