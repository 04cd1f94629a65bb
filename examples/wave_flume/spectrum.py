#!/usr/bin/python3
"""Wave flume, irregular sea: the gauges' wave spectra against the JONSWAP spectrum asked for.

  spectrum.py RUN_DIR [--wavemaker NAME] [--start T0] [--max-hm0-error F] [--figure PNG]

The wavemaker (PistonWavemaker or FlapWavemaker with spectrum = "jonswap", docs/user-guide.md,
"Making waves") makes N regular components at whole multiples n dw of the band's width, so the
sea repeats after 2 pi / dw. The sea asked for (H_s, T_p, gamma) and the components' frequencies
are read from the run's run.json ("wavemakers", format_version 9), so nothing is typed twice.
Over one repeat period from T0 each gauge's record is fitted by least squares with those N
frequencies (and a mean): each component's height at the gauge, with no leakage between them.
Printed per gauge: the significant height H_m0 = 4 sqrt(m0) of the band, its ratio to the asked
H_s, and the peak period of the measured spectrum smoothed over five components; the target is
JONSWAP written here from DNV-RP-C205 §3.5.5 at the recorded frequencies, scaled as the
wavemaker scales it (4 sqrt(m0) = H_s over its components), and compared with the heights the
wavemaker recorded. The paddle's own record (sensor paddle_x, if there) is fitted too: the
stroke it made.
--max-hm0-error F fails the run when H_m0 at the first gauge is off H_s by more than the fraction F
(the SPH wave loses height as it travels: 10-16 % per metre at this resolution for the regular
wave, docs/validation.md "Making waves")."""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import finish_figure, pyplot, read_run, write_analysis  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("run_dir")
parser.add_argument("--wavemaker", metavar="NAME",
                    help="the wavemaker's name (default: the run's one irregular wavemaker)")
parser.add_argument("--start", type=float, default=12.0,
                    help="start of the analysed repeat period (after the ramp and the sea's travel)")
parser.add_argument("--max-hm0-error", type=float, metavar="F")
parser.add_argument("--figure")
args = parser.parse_args()

run, sensors = read_run(args.run_dir)
if run.get("format_version", 0) < 9 or "wavemakers" not in run:
    sys.exit(f"{args.run_dir}/run.json: format_version {run.get('format_version')} records no "
             "wavemakers (version 9 and later do); run the scene again with this fsi-server")
seas = [w for w in run["wavemakers"] if w["spectrum"] != "regular"
        and (args.wavemaker is None or w["name"] == args.wavemaker)]
if len(seas) != 1:
    names = ", ".join(f"{w['name']} ({w['spectrum']})" for w in run["wavemakers"]) or "none"
    sys.exit(f"{args.run_dir}: {len(seas)} irregular wavemakers match (the run's wavemakers: "
             f"{names}); give spectrum = \"jonswap\" to one, or name it with --wavemaker")
sea = seas[0]
hs, tp, gamma = sea["height"], sea["period"], sea["peak_enhancement"]
wp = 2 * math.pi / tp
omegas = np.array(sea["components"]["omega"])
repeat = sea["repeat_period"]
width = 2 * math.pi / repeat


def jonswap(w):
    sigma = np.where(w <= wp, 0.07, 0.09)
    alpha = np.exp(-(w - wp) ** 2 / (2 * sigma ** 2 * wp ** 2))
    pm = 5.0 / 16.0 * hs ** 2 * wp ** 4 * w ** -5.0 * np.exp(-1.25 * (w / wp) ** -4.0)
    return (1 - 0.287 * math.log(gamma)) * pm * gamma ** alpha


target = 2 * np.sqrt(2 * jonswap(omegas) * width)  # component heights
target *= hs / (4 * math.sqrt(np.sum(target ** 2) / 8))
recorded = np.array(sea["components"]["height"])
mismatch = float(np.max(np.abs(recorded - target)) / np.max(target))
if mismatch > 1e-9:
    sys.exit(f"{args.run_dir}: the wavemaker's component heights differ from JONSWAP here by "
             f"{mismatch:.2e} of the largest: fsi-server and this script disagree on the spectrum")

time = np.array(sensors["time"])
t0, t1 = args.start, args.start + repeat
if time[-1] < t1 - 1e-9:
    sys.exit(f"{args.run_dir}: the run ends at t = {time[-1]:.3f} s, before one repeat period "
             f"({repeat:.2f} s) from {t0} s has passed; run to {t1:.1f} s or lower --start")
inside = (time >= t0) & (time <= t1)
tt = time[inside]
basis = np.column_stack([np.cos(np.outer(tt, omegas)), np.sin(np.outer(tt, omegas)),
                         np.ones_like(tt)])


def heights(values):
    coefficients = np.linalg.lstsq(basis, values, rcond=None)[0]
    n = len(omegas)
    return 2 * np.hypot(coefficients[:n], coefficients[n:2 * n])


def peak_period(h):
    smooth = np.convolve(h ** 2, np.ones(5) / 5, mode="same")
    return 2 * math.pi / omegas[int(np.argmax(smooth))]


def hm0(h):
    return 4 * math.sqrt(np.sum(h ** 2) / 8)


print(f"{args.run_dir}: JONSWAP H_s = {hs} m, T_p = {tp} s, gamma {gamma} (wavemaker "
      f"{sea['name']}); {len(omegas)} components {omegas[0]:.3f}-{omegas[-1]:.3f} 1/s, window "
      f"{t0:.2f}-{t1:.2f} s (one repeat period)")
result = {"window": [t0, t1], "gauges": {}}
if "paddle_x" in sensors:
    stroke = heights(np.array(sensors["paddle_x"])[inside])
    print(f"  the paddle: largest component stroke {np.max(stroke):.5f} m at "
          f"{omegas[int(np.argmax(stroke))]:.3f} 1/s")
gauges = sorted(name for name in sensors if name.endswith("_elevation") and name.startswith("g")
                and name[1:-len("_elevation")].isdigit())
if not gauges:
    sys.exit(f"{args.run_dir}: no FreeSurfaceProbe column gXY_elevation in sensors.csv")
measured = {}
for name in gauges:
    h = heights(np.array(sensors[name])[inside])
    measured[name] = h
    x = int(name[1:-len("_elevation")]) / 10.0
    ratio = hm0(h) / hs
    print(f"  x = {x:.1f} m: H_m0 = {hm0(h):.4f} m ({100 * (ratio - 1):+.1f} % from H_s), "
          f"T_p = {peak_period(h):.3f} s ({100 * (peak_period(h) / tp - 1):+.1f} %)")
    result["gauges"][name] = {"x": x, "Hm0": hm0(h), "Tp": peak_period(h)}
first_gauge = gauges[0]
error = hm0(measured[first_gauge]) / hs - 1
result["Hm0_error_first_gauge"] = error
write_analysis(args.run_dir, result)
failures = 0
if args.max_hm0_error is not None:
    ok = abs(error) <= args.max_hm0_error
    failures += not ok
    print(f"{'ok  ' if ok else 'FAIL'} H_m0 at {first_gauge[:-len('_elevation')]}: "
          f"{100 * error:+.1f} % from H_s (at most {100 * args.max_hm0_error:g} %)")
plt = pyplot("spectrum.py") if args.figure else None
if plt:
    figure, axes = plt.subplots(figsize=(8, 4))
    density = 1 / (8 * width)  # S(w) of a component of height h: h^2 / (8 dw)
    smooth_target = np.convolve(target ** 2, np.ones(3) / 3, mode="same")
    axes.plot(omegas, smooth_target * density, "k-", linewidth=2, label="JONSWAP asked for")
    for name in gauges:
        smooth = np.convolve(measured[name] ** 2, np.ones(3) / 3, mode="same")
        axes.plot(omegas, smooth * density, linewidth=0.9,
                  label=f"x = {int(name[1:-len('_elevation')]) / 10:.1f} m")
    axes.set_xlabel("omega [1/s]")
    axes.set_ylabel("S(omega) [m^2 s]")
    finish_figure(figure, axes, f"{os.path.basename(os.path.normpath(args.run_dir))}: wave spectra "
                  "(each curve a 3-component average)", args.figure, legend_location="upper right")
sys.exit(1 if failures else 0)
