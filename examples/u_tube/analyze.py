#!/usr/bin/python3
"""U-tube liquid column: the period of the free oscillation against linear theory
T0 = 2 pi sqrt(L / (2 g)) (L the column's length along the tube's centre line), and its decay.

  analyze.py RUN_DIR [--tolerance F]

The column's displacement s(t) = (eta_right - eta_left) / 2 is read from the two free-surface
probes (the legs are alike, so s = 0 at rest and the probes' own offset cancels). The period is twice the mean time between successive
zero crossings of s (linear interpolation between samples), over every crossing of the run; the decay is the logarithmic decrement of successive extrema of |s| (one per half
period), reported as the damping ratio zeta = delta / sqrt(4 pi^2 + delta^2) per full period.
The zero crossings give the damped period T_d; the comparison with T0 (an undamped oscillator's)
uses the natural period T_n = T_d sqrt(1 - zeta^2) (both are printed; they differ by 1 % at
zeta = 0.14).
A cross-check: the flux through the bottom channel is b ds/dt (continuity), so its amplitude is
compared with omega b s0."""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import read_run, write_analysis, zero_crossings  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--tolerance", type=float, help="fail if |T / T0 - 1| exceeds this")
    args = parser.parse_args()

    run, sensors = read_run(args.run_dir)
    params = run["parameters_flat"]
    g = math.hypot(*run["model"]["gravity"])
    length = params["Geometry.L"]
    width = params["Geometry.b"]
    period_theory = 2.0 * math.pi * math.sqrt(length / (2.0 * g))
    time = sensors["time"]
    if not all(sensors["left_wet"]) or not all(sensors["right_wet"]):
        print("analyze: a free-surface probe found no water at some row; see sensors.csv", file=sys.stderr)
        return 1
    s = [0.5 * (r - l) for l, r in zip(sensors["left_elevation"], sensors["right_elevation"])]
    s0 = s[0]
    crossings = zero_crossings(time, s)
    if len(crossings) < 3:
        print(f"analyze: only {len(crossings)} zero crossings of s(t) in {time[-1]:.3f} s; run at least "
              f"1.5 periods ({1.5 * period_theory:.2f} s)", file=sys.stderr)
        return 1
    period = 2.0 * (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    # Extrema of |s| between successive crossings (and before the first one: the release).
    bounds = [0.0] + crossings
    amplitudes = []
    for a, b in zip(bounds, bounds[1:]):
        window = [abs(v) for t, v in zip(time, s) if a <= t <= b]
        if window:
            amplitudes.append(max(window))
    decrements = [math.log(a / b) for a, b in zip(amplitudes, amplitudes[1:]) if a > 0 and b > 0]
    delta = 2.0 * sum(decrements) / len(decrements) if decrements else float("nan")  # per full period
    zeta = delta / math.sqrt(4.0 * math.pi ** 2 + delta ** 2)
    flux = sensors["channel_flux"]
    flux_amplitude = max(abs(q) for q in flux)
    omega = 2.0 * math.pi / period
    flux_expected = omega * width * abs(s0)
    natural = period * math.sqrt(1.0 - zeta ** 2) if math.isfinite(zeta) else period
    error = natural / period_theory - 1.0
    result = {"length": length, "period_theory": period_theory, "period_damped": period,
              "period": natural, "period_error": error,
              "zero_crossings": crossings, "initial_displacement": s0, "amplitudes": amplitudes,
              "log_decrement_per_period": delta, "damping_ratio": zeta,
              "flux_amplitude": flux_amplitude, "flux_amplitude_expected": flux_expected}
    print(f"U-tube, L = {length:.4g} m, d = {params['LIGGGHTS_SPH_parameters.particlespacing']} m: "
          f"natural period {natural:.4f} s (damped {period:.4f} s from {len(crossings)} zero crossings), "
          f"linear theory 2 pi sqrt(L/2g) = {period_theory:.4f} s, error {100 * error:+.2f} %")
    print(f"  displacement at release {1000 * s0:.2f} mm; amplitudes per half period [mm]: "
          + ", ".join(f"{1000 * a:.2f}" for a in amplitudes))
    print(f"  logarithmic decrement {delta:.4f} per period, damping ratio {zeta:.4f}; channel flux amplitude "
          f"{flux_amplitude:.4g} m^2/s against omega b s0 = {flux_expected:.4g} m^2/s")
    write_analysis(args.run_dir, result)
    if args.tolerance is not None and abs(error) > args.tolerance:
        print(f"FAIL: period error {100 * error:+.2f} % outside +-{100 * args.tolerance:g} %")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
