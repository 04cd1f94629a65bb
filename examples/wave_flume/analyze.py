#!/usr/bin/python3
"""Wave flume: how much of the wave the flume's end sends back, from the five gauges.

  analyze.py RUN_DIR [--window T0 T1] [--period T] [--depth H] [--stroke S] [--flap L]
             [--height H] [--at X] [--gauges NAME=X ...] [--max-reflection F]
             [--min-reflection F] [--max-height-error F] [--figure PNG] [--compare RUN_DIR]

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
below F (the reflecting flume). --max-height-error F fails it when the incident height fitted
back to the paddle (x = 0) is off the linear wavemaker theory's by more than the fraction F.

Another flume: --period and --depth give its wave (defaults: this example's 1.4 s, 0.4 m),
--stroke its paddle's full stroke for the wavemaker theory's height (default 0.06 m; with --flap L
a flap's stroke at the still surface, hinged L below it), or --height the height a
PistonWavemaker or FlapWavemaker block was asked for (its theory's; the stroke is then not
needed), --at the x
where K_r is referred to (default 3.0 m), and --gauges the FreeSurfaceProbes to use with their x
(default: every probe named gXY, at x = X.Y m). At least four gauges (the fit has five unknowns:
two complex amplitudes and the decay; three gauges of this run gave 0.075 against five's 0.028),
spread over a fraction of a wavelength, none two a multiple of half a wavelength apart (where
the split is singular)."""
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
parser.add_argument("--period", type=float, default=1.4)
parser.add_argument("--depth", type=float, default=0.40)
parser.add_argument("--stroke", type=float, default=0.06)
parser.add_argument("--flap", type=float, metavar="L",
                    help="the paddle is a flap hinged L below the still surface (--stroke at it)")
parser.add_argument("--height", type=float,
                    help="the wave height asked of the scene's wavemaker block (instead of --stroke)")
parser.add_argument("--max-height-error", type=float, metavar="F")
parser.add_argument("--power-from", type=float, default=4.2,
                    help="start of the drive's power average (whole periods to the window's end)")
parser.add_argument("--at", type=float, default=3.0)
parser.add_argument("--gauges", nargs="+", metavar="NAME=X")
parser.add_argument("--max-reflection", type=float)
parser.add_argument("--min-reflection", type=float)
parser.add_argument("--figure")
parser.add_argument("--compare", metavar="RUN_DIR",
                    help="a second run (e.g. the flume without its sponge) drawn below")
args = parser.parse_args()

T, depth, g = args.period, args.depth, 9.81
w = 2 * math.pi / T
k = w * w / g
for _ in range(200):
    k = w * w / (g * math.tanh(k * depth))
# Linear wavemaker theory (Dean & Dalrymple 1991, §6.2): H / S = 4 k sinh(kh) I / (sinh 2kh + 2kh),
# I the integral over the depth of the paddle's profile times cosh k(h - z): sinh(kh) / k for a
# piston, sinh(kh) / k - (cosh kh - cosh k(h - L)) / (L k^2) for a flap hinged L below the surface.
kh = k * depth
moved = math.sinh(kh) / k
if args.flap:
    if not 0 < args.flap <= depth:
        sys.exit(f"--flap {args.flap}: the hinge's depth must be in (0, {depth}] (the water's depth)")
    moved -= (math.cosh(kh) - math.cosh(k * (depth - args.flap))) / (args.flap * k * k)
H_per_S = 4 * k * math.sinh(kh) * moved / (math.sinh(2 * kh) + 2 * kh)
H_theory = args.height if args.height else args.stroke * H_per_S

run, sensors = read_run(args.run_dir)
time = np.array(sensors["time"])
t0, t1 = args.window
if time[-1] < t1:
    sys.exit(f"{args.run_dir}: the run ends at t = {time[-1]:.3f} s, before the window's end "
             f"{t1} s; run the scene to its end_time (12 s)")
inside = (time >= t0) & (time <= t1)
if args.gauges:
    pairs = [item.split("=", 1) for item in args.gauges]
    if any(len(pair) != 2 for pair in pairs):
        sys.exit("--gauges: give each as NAME=X, e.g. g10=1.0 (NAME: the FreeSurfaceProbe's name)")
    gauges, xs = [name + "_elevation" for name, _ in pairs], np.array([float(x) for _, x in pairs])
else:
    gauges = sorted(name for name in sensors
                    if name.endswith("_elevation") and name[1:-len("_elevation")].isdigit()
                    and name.startswith("g"))
    xs = np.array([int(name[1:-len("_elevation")]) / 10.0 for name in gauges])
missing = [name for name in gauges if name not in sensors]
if missing or len(gauges) < 4:
    sys.exit(f"{args.run_dir}: need at least four FreeSurfaceProbe columns; missing {missing}, "
             f"found {gauges} (name them gXY for x = X.Y m, or give --gauges NAME=X ...)")
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
x_zone = args.at
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
# The power the drive puts in, over whole periods after the ramp: the PrescribedMotion's force
# (torque) times the paddle's velocity (angular velocity), against the linear wave's energy flux
# E c_g = rho g H^2 / 8 c_g (rho = 1000 kg/m^3).
power = None
for drive, motion in (("paddle_force", "paddle_x"), ("paddle_torque", "paddle_angle")):
    if drive in sensors and motion in sensors:
        p0 = args.power_from
        p1 = p0 + T * math.floor((min(time[-1], t1) - p0) / T)
        over = (time >= p0) & (time <= p1)
        rate = np.gradient(np.array(sensors[motion]), time)
        power = float(np.mean((np.array(sensors[drive]) * rate)[over]))
        c_g = 0.5 * (w / k) * (1 + 2 * kh / math.sinh(2 * kh))
        flux = 1000 * g * H_theory ** 2 / 8 * c_g
        print(f"  the drive's mean power {power:.3f} W/m over {p0:.1f}-{p1:.1f} s ({drive} times "
              f"the rate of {motion}), {100 * (power / flux - 1):+.1f} % from the linear wave's "
              f"E c_g = {flux:.3f} W/m")
failures = 0
height_error = 2 * abs(aI) / H_theory - 1
if args.max_height_error is not None:
    ok = abs(height_error) <= args.max_height_error
    failures += not ok
    print(f"{'ok  ' if ok else 'FAIL'} incident height at the paddle {2 * abs(aI):.4f} m, "
          f"{100 * height_error:+.1f} % from the theory's {H_theory:.4f} m (at most "
          f"{100 * args.max_height_error:g} %)")
for limit, holds, relation in ((args.max_reflection, lambda v, f: v <= f, "at most"),
                               (args.min_reflection, lambda v, f: v >= f, "at least")):
    if limit is None:
        continue
    ok = holds(reflection, limit)
    failures += not ok
    print(f"{'ok  ' if ok else 'FAIL'} K_r at x = {x_zone} m: {reflection:.3f} ({relation} {limit})")
write_analysis(args.run_dir, {"window": [t0, t1], "k": k, "H_theory": H_theory,
                              "gauges_x": list(xs), "gauges_H": [2 * abs(b) for b in B],
                              "H_incident": 2 * abs(aI), "H_incident_error": height_error,
                              "H_reflected": 2 * abs(aR), "decay": delta,
                              "reflection": reflection, "reflection_no_decay": abs(aR0) / abs(aI0),
                              "drive_power": power})
plt = pyplot("analyze.py") if args.figure else None
if plt:
    runs = [(args.run_dir, sensors, f"K_r = {reflection:.3f}")]
    if args.compare:
        _, other = read_run(args.compare)
        runs.append((args.compare, other, "the run compared"))
    figure, panels = plt.subplots(len(runs), 1, figsize=(8, 3.2 * len(runs)), sharex=True,
                                  squeeze=False)
    for (run_dir, columns, what), axes in zip(runs, panels[:, 0]):
        for name, x in zip(gauges, xs):
            axes.plot(columns["time"], np.array(columns[name]) - depth, label=f"x = {x:.1f} m",
                      linewidth=0.8)
        axes.axvspan(t0, t1, color="0.9")
        axes.set_ylabel("elevation [m]")
        finish_figure(figure, axes, f"{os.path.basename(os.path.normpath(run_dir))}: {what}",
                      args.figure)
    panels[-1, 0].set_xlabel("t [s]")
    figure.savefig(args.figure, dpi=120)
sys.exit(1 if failures else 0)
