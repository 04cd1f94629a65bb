#!/usr/bin/python3
"""Wave flume: how much of the wave the flume's end sends back, from the five gauges.

  analyze.py RUN_DIR [--window T0 T1] [--max-reflection F] [--min-reflection F] [--figure PNG]

Each gauge's first harmonic B_j (eta = Re(B_j e^{i w t}) plus a mean and a drift, least squares
over the window) is split into an incident and a reflected wave, B_j = a_I e^{-(ik + delta) x_j} +
a_R e^{(ik + delta) x_j} (Mansard & Funke 1980, with the wave's numerical decay delta along the
flume fitted: the SPH wave loses height as it travels, docs/validation.md "Wave absorption"), k
from the linear dispersion relation. Printed: the height per gauge, H_I and H_R, the decay, and
the reflection coefficient K_r = |a_R| / |a_I| at x = 3.0 m (where the sponge starts) and as seen
at the gauges without the decay. The default window 9.0-11.8 s (two periods) starts after the
wall's reflection has come back past every gauge (group velocity 1.30 m/s: the wave front
reaches the wall at about 4.2 s and the reflection x = 1.0 m at about 7.6 s).
--max-reflection F fails the run when K_r at x = 3.0 exceeds F; --min-reflection F when it is
below F (the reflecting flume)."""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import finish_figure, pyplot, read_run, write_analysis  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("run_dir")
parser.add_argument("--window", nargs=2, type=float, default=[9.0, 11.8])
parser.add_argument("--max-reflection", type=float)
parser.add_argument("--min-reflection", type=float)
parser.add_argument("--figure")
args = parser.parse_args()

T, depth, g = 1.4, 0.40, 9.81
w = 2 * math.pi / T
k = w * w / g
for _ in range(200):
    k = w * w / (g * math.tanh(k * depth))
# Linear piston wavemaker (Dean & Dalrymple): H / S = 2 (cosh 2kh - 1) / (sinh 2kh + 2kh).
stroke = 0.06
H_theory = stroke * 2 * (math.cosh(2 * k * depth) - 1) / (math.sinh(2 * k * depth) + 2 * k * depth)

run, sensors = read_run(args.run_dir)
time = np.array(sensors["time"])
t0, t1 = args.window
if time[-1] < t1:
    sys.exit(f"{args.run_dir}: the run ends at t = {time[-1]:.3f} s, before the window's end "
             f"{t1} s; run the scene to its end_time (12 s)")
inside = (time >= t0) & (time <= t1)
gauges = sorted((name for name in sensors if name.endswith("_elevation")), key=lambda n: n)
xs = np.array([int(name[1:3]) / 10.0 for name in gauges])
B = []
for name in gauges:
    eta = np.array(sensors[name])[inside]
    tt = time[inside]
    basis = np.column_stack([np.cos(w * tt), np.sin(w * tt), np.ones_like(tt), tt - tt.mean()])
    a, b, _, _ = np.linalg.lstsq(basis, eta, rcond=None)[0]
    B.append(complex(a, -b))
B = np.array(B)


def split(delta):
    m = np.column_stack([np.exp(-(1j * k + delta) * xs), np.exp((1j * k + delta) * xs)])
    solution = np.linalg.lstsq(m, B, rcond=None)[0]
    return np.linalg.norm(m @ solution - B), solution


best = min(((split(d)[0], d) for d in np.linspace(0.0, 0.4, 401)))
residual, delta = best
_, (aI, aR) = split(delta)
_, (aI0, aR0) = split(0.0)
x_zone = 3.0
reflection = abs(aR) * math.exp(delta * x_zone) / (abs(aI) * math.exp(-delta * x_zone))
print(f"{args.run_dir}: window {t0}-{t1} s, k = {k:.4f} 1/m (lambda {2 * math.pi / k:.3f} m), "
      f"linear wavemaker theory H = {H_theory:.4f} m")
print("  first-harmonic height per gauge: " +
      ", ".join(f"x = {x:.1f} m: {2 * abs(b):.4f} m" for x, b in zip(xs, B)))
print(f"  incident H_I = {2 * abs(aI):.4f} m at x = 0 ({2 * abs(aI0):.4f} m without decay), "
      f"decay delta = {delta:.3f} 1/m (height lost over 1 m: {100 * (1 - math.exp(-delta)):.1f} %)")
print(f"  reflected H_R = {2 * abs(aR):.4f} m at x = 0; fit residual {residual / np.linalg.norm(B):.3f}")
print(f"  K_r = {reflection:.3f} at x = {x_zone} m (decay fitted), {abs(aR0) / abs(aI0):.3f} at the "
      f"gauges (no decay)")
failures = 0
for limit, holds, relation in ((args.max_reflection, lambda v, f: v <= f, "at most"),
                               (args.min_reflection, lambda v, f: v >= f, "at least")):
    if limit is None:
        continue
    ok = holds(reflection, limit)
    failures += not ok
    print(f"{'ok  ' if ok else 'FAIL'} K_r at x = {x_zone} m: {reflection:.3f} ({relation} {limit})")
write_analysis(args.run_dir, {"window": [t0, t1], "k": k, "H_theory": H_theory,
                              "gauges_x": list(xs), "gauges_H": [2 * abs(b) for b in B],
                              "H_incident": 2 * abs(aI), "H_reflected": 2 * abs(aR), "decay": delta,
                              "reflection": reflection, "reflection_no_decay": abs(aR0) / abs(aI0)})
if args.figure:
    plt = pyplot("analyze.py")
    figure, axes = plt.subplots(figsize=(8, 4))
    for name, x in zip(gauges, xs):
        axes.plot(time, np.array(sensors[name]) - depth, label=f"x = {x:.1f} m", linewidth=0.8)
    axes.axvspan(t0, t1, color="0.9")
    axes.set_xlabel("t [s]")
    axes.set_ylabel("elevation [m]")
    finish_figure(figure, axes, f"Wave gauges, K_r = {reflection:.3f}", args.figure)
sys.exit(1 if failures else 0)
