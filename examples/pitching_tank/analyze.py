#!/usr/bin/python3
"""Sloshing in a pitching tank (Akyildiz & Unal 2006, Fig. 5): the pressure at transducers 2 and 8
against the experiment.

  analyze.py RUN_DIR [RUN_DIR ...] [--mean-tolerance F] [--amplitude-tolerance F]
             [--lag-tolerance S] [--figure PNG] [--reference-dir DIR]

Transducer 2 (the right wall, 0.17 m above the floor, always wet): over the experiment's points
within the run, a least-squares fit of p(t) = a + b sin(w t) + c cos(w t) at the pitching's w
(2 rad/s) to the experiment's points and to the run's curve. Stated, and judged by the options:
  - the amplitude sqrt(b^2 + c^2) against the experiment's (relative);
  - the lag of the run's fitted wave behind the experiment's [s] (negative: the run leads);
  - the mean a against the still-water pressure rho g (depth - 0.17 m) of the depth the particles
    fill (the fluid box holds whole cells, so a coarse spacing fills less than 0.465 m): the
    pitching's mean is the hydrostatic one to second order in the 4 degrees. Not against the
    experiment's mean, which lies 11 % above the still water of its own 0.465 m (its transducer 8
    reads about 240 Pa while dry: an offset of the record, README.md); that mean is stated;
  - the RMS of (p - its mean) - (p_exp - its mean) at the experiment's points, relative to the
    experiment's amplitude (stated only).
Transducer 8 (the left wall, 0.45 m up, 1.5 cm below the still surface: wet and dry in turn): its
largest and smallest values over the experiment's points, stated only (the experiment reads about
0.24 kPa while the transducer is dry, the run 0).

Each --*-tolerance fails the run when its figure is outside it; without one the figure is only
stated. The data: ../shared/reference-data/akyildiz_unal_2006_pitch_probe{2,8}.dat (t [s], p
[kPa]; README.md of that folder names the source), or --reference-dir."""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import (SHARED_REFERENCE_DATA, finish_figure, interpolate_clamped, pyplot,  # noqa: E402
                         judge_runs, read_reference_points, read_run, require_run)

REFERENCE_FILES = {"p2": "akyildiz_unal_2006_pitch_probe2.dat", "p8": "akyildiz_unal_2006_pitch_probe8.dat"}
P2_HEIGHT = 0.17  # transducer 2 above the floor [m] (the scene's Geometry.p2_height)


def read_curve(path):
    """The experiment's (t [s], p [Pa]) points."""
    points = read_reference_points(path, "give --reference-dir DIR (the project's shared reference-data folder, "
                                         "with the akyildiz_unal_2006_* files)")
    return [(t, 1000.0 * p) for t, p in points]


def harmonic_fit(times, values, omega):
    """(mean, amplitude, phase) of the least-squares a + b sin(w t) + c cos(w t): the amplitude
    sqrt(b^2 + c^2), the phase atan2(c, b) (the wave is amplitude sin(w t + phase))."""
    import numpy as np
    t = np.asarray(times, dtype=float)
    basis = np.column_stack([np.ones_like(t), np.sin(omega * t), np.cos(omega * t)])
    a, b, c = np.linalg.lstsq(basis, np.asarray(values, dtype=float), rcond=None)[0]
    return float(a), float(math.hypot(b, c)), float(math.atan2(c, b))


def analyze_run(run_dir, references):
    require_run(run_dir, "pitching tank")
    run, sensors = read_run(run_dir)
    p = run["parameters_flat"]
    omega = p["Geometry.omega"]
    spacing = p["Fluid.spacing"]
    filled = math.floor(p["Geometry.depth"] / spacing + 1e-9) * spacing
    time = sensors["time"]
    experiment = [(t, v) for t, v in references["p2"] if t <= time[-1]]
    if len(experiment) < 4:
        raise SystemExit(f"analyze: {run_dir} ends at t = {time[-1]:.3g} s, before four of the experiment's points "
                         f"(its first at {references['p2'][0][0]:.3g} s); run longer (Resolution.end_time)")
    t_exp = [t for t, _ in experiment]
    window = [(t, v) for t, v in zip(time, sensors["p2_pressure"]) if t_exp[0] <= t <= t_exp[-1]]
    ours = harmonic_fit([t for t, _ in window], [v for _, v in window], omega)
    theirs = harmonic_fit(t_exp, [v for _, v in experiment], omega)
    # The lag of our wave behind theirs, the phase difference wrapped to (-pi, pi].
    phase = math.remainder(theirs[2] - ours[2], 2.0 * math.pi)
    # The swing's deviation: each curve about its own mean (the means are compared above).
    rms = math.sqrt(sum((interpolate_clamped(time, sensors["p2_pressure"], t) - ours[0] - v + theirs[0]) ** 2
                        for t, v in experiment) / len(experiment))
    gravity = math.hypot(*run["model"]["gravity"])
    density = p["Fluid.density"]
    p8_points = [(t, v) for t, v in references["p8"] if t <= time[-1]]
    p8_ours = [interpolate_clamped(time, sensors["p8_pressure"], t) for t, _ in p8_points]
    return {
        "run_dir": run_dir, "spacing": spacing, "end_time": time[-1], "time": time,
        "p2": sensors["p2_pressure"], "p8": sensors["p8_pressure"],
        "window": [t_exp[0], t_exp[-1]], "points": len(experiment),
        "filled_depth": filled, "still_water_p2": density * gravity * (filled - P2_HEIGHT),
        "still_water_p2_full_depth": density * gravity * (p["Geometry.depth"] - P2_HEIGHT),
        "p2_mean": ours[0], "p2_amplitude": ours[1], "experiment_p2_mean": theirs[0],
        "experiment_p2_amplitude": theirs[1],
        "mean_error": ours[0] / (density * gravity * (filled - P2_HEIGHT)) - 1.0,
        "experiment_mean_over_still_water": theirs[0] / (density * gravity * (p["Geometry.depth"] - P2_HEIGHT)) - 1.0,
        "amplitude_error": ours[1] / theirs[1] - 1.0,
        "lag": phase / omega, "rms_of_amplitude": rms / theirs[1],
        "p8_max": max(p8_ours), "p8_min": min(p8_ours),
        "experiment_p8_max": max(v for _, v in p8_points), "experiment_p8_min": min(v for _, v in p8_points),
    }


def report(result):
    r = result
    print(f"pitching tank, d = {1000 * r['spacing']:g} mm (water {r['filled_depth']:.4g} m deep), "
          f"t = 0-{r['end_time']:.3g} s ({r['run_dir']}):")
    print(f"  transducer 2 over {r['window'][0]:.3g}-{r['window'][1]:.3g} s ({r['points']} points of the experiment), "
          f"fitted at the pitching's frequency:")
    print(f"    mean {r['p2_mean']:.0f} Pa against the still water of the depth filled {r['still_water_p2']:.0f} Pa "
          f"({100 * r['mean_error']:+.1f} %); the experiment's mean {r['experiment_p2_mean']:.0f} Pa lies "
          f"{100 * r['experiment_mean_over_still_water']:+.1f} % from the still water of its 0.465 m "
          f"({r['still_water_p2_full_depth']:.0f} Pa)")
    print(f"    amplitude {r['p2_amplitude']:.0f} Pa against {r['experiment_p2_amplitude']:.0f} Pa "
          f"({100 * r['amplitude_error']:+.1f} %); lag {r['lag']:+.3f} s (negative: ahead of the experiment); "
          f"RMS of the swings' difference {100 * r['rms_of_amplitude']:.0f} % of the experiment's amplitude")
    print(f"  transducer 8 at the experiment's points: {r['p8_min']:.0f} to {r['p8_max']:.0f} Pa, the experiment "
          f"{r['experiment_p8_min']:.0f} to {r['experiment_p8_max']:.0f} Pa (it reads about 240 Pa dry, the run 0)")


def judge(result, args):
    """The figures outside their tolerances, as messages."""
    failures = []
    for tolerance, value, what, unit in (
            (args.mean_tolerance, result["mean_error"], "mean of transducer 2 against the still water", "%"),
            (args.amplitude_tolerance, result["amplitude_error"], "amplitude of transducer 2", "%"),
            (args.lag_tolerance, result["lag"], "lag of transducer 2", "s")):
        if tolerance is not None and not abs(value) <= tolerance:
            shown = f"{100 * value:+.1f} % outside {100 * tolerance:g} %" if unit == "%" else \
                f"{value:+.3f} s outside {tolerance:g} s"
            failures.append(f"{what}: {shown} (d = {1000 * result['spacing']:g} mm)")
    return failures


def draw(results, references, path):
    plt = pyplot("analyze.py")
    if plt is None:
        return
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(7.2, 6.4), sharex=True)
    for axes, key, label in ((top, "p2", "transducer 2 (right wall, 0.17 m)"),
                             (bottom, "p8", "transducer 8 (left wall, 0.45 m)")):
        axes.plot([t for t, _ in references[key]], [v / 1000 for _, v in references[key]], "ko",
                  label="experiment (Akyildiz & Unal 2006)")
        for result in results:
            axes.plot(result["time"], [v / 1000 for v in result[key]], lw=1.0,
                      label=f"SPH, d = {1000 * result['spacing']:g} mm")
        axes.set_ylabel(f"{label} [kPa]")
    bottom.grid(True, alpha=0.3)
    bottom.set_xlabel("t [s]")
    finish_figure(figure, top, "Pitching tank, 4 deg at 2 rad/s: wall pressures", path, legend_location="lower left")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dirs", nargs="+")
    parser.add_argument("--reference-dir", default=SHARED_REFERENCE_DATA,
                        help="folder with the akyildiz_unal_2006_* files (default: ../shared/reference-data)")
    parser.add_argument("--mean-tolerance", type=float,
                        help="fail if transducer 2's mean is further from the still water of the depth filled")
    parser.add_argument("--amplitude-tolerance", type=float,
                        help="fail if transducer 2's amplitude is further from the experiment's")
    parser.add_argument("--lag-tolerance", type=float, help="fail if transducer 2's wave lags or leads by more [s]")
    parser.add_argument("--figure", help="draw both transducers of every run with the experiment (PNG)")
    args = parser.parse_args()

    references = {key: read_curve(os.path.join(args.reference_dir, name)) for key, name in REFERENCE_FILES.items()}
    results = [analyze_run(run_dir, references) for run_dir in args.run_dirs]
    status = judge_runs(results, report, lambda result: judge(result, args), curves=("time", "p2", "p8"))
    if args.figure:
        draw(results, references, args.figure)
    return status


if __name__ == "__main__":
    sys.exit(main())
