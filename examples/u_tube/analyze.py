#!/usr/bin/python3
"""U-tube liquid column: the period of the free oscillation against linear theory
T0 = 2 pi sqrt(L / (2 g)) (L the column's length along the tube's centre line), and its decay.

  analyze.py RUN_DIR [--tolerance F]

The column's displacement s(t) = (eta_right - eta_left) / 2 is read from the two free-surface
probes (the legs are alike, so s = 0 at rest and the probes' own offset cancels).

The period and the decay come from a least-squares fit of c + exp(-sigma t) (a cos(w t) +
b sin(w t)) to all of s(t) from the release on (fsi_results.damped_fit, the estimator of the
sloshing free decay too): the damped period T_d = 2 pi / w, the damping ratio
zeta = sigma / sqrt(w^2 + sigma^2), and the natural period T_n = 2 pi / sqrt(w^2 + sigma^2) of the
undamped oscillator, which is compared with T0 (--tolerance). The constant c takes up a mean
level of s slightly off zero (the settled legs are not exactly alike at the probes); zero
crossings counted over an odd number of half periods would carry that offset into T_d.

Two cross-checks are printed: the damped period from the zero crossings of s over whole periods
only (an even number of half periods, so that a constant offset cancels), and the logarithmic
decrement of the extrema of |s| (one per half period), as a damping ratio per full period.
A cross-check: the flux through the bottom channel is b ds/dt (continuity), so its amplitude is
compared with omega b s0."""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import damped_fit, read_run, write_analysis, zero_crossings  # noqa: E402


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
    fit = damped_fit(time, s, 2.0 * math.pi / period_theory)
    natural, damped, zeta = fit["natural_period"], fit["damped_period"], fit["damping_ratio"]
    error = natural / period_theory - 1.0
    # Cross-check 1: zero crossings over whole periods (an even count of half periods).
    whole = len(crossings) - 1 - (len(crossings) - 1) % 2
    crossing_period = (crossings[whole] - crossings[0]) / (whole / 2) if whole >= 2 else None
    # Cross-check 2: extrema of |s| between successive crossings (and before the first: the release).
    bounds = [0.0] + crossings
    amplitudes = []
    for a, b in zip(bounds, bounds[1:]):
        window = [abs(v) for t, v in zip(time, s) if a <= t <= b]
        if window:
            amplitudes.append(max(window))
    decrements = [math.log(a / b) for a, b in zip(amplitudes, amplitudes[1:]) if a > 0 and b > 0]
    delta = 2.0 * sum(decrements) / len(decrements) if decrements else float("nan")  # per full period
    zeta_extrema = delta / math.sqrt(4.0 * math.pi ** 2 + delta ** 2)
    flux = sensors["channel_flux"]
    flux_amplitude = max(abs(q) for q in flux)
    flux_expected = 2.0 * math.pi / damped * width * abs(s0)
    result = {"length": length, "period_theory": period_theory, "period_damped": damped,
              "period": natural, "period_error": error, "damping_ratio": zeta,
              "fit_rms_residual": fit["rms_residual"],
              "zero_crossings": crossings, "zero_crossing_period_whole_periods": crossing_period,
              "initial_displacement": s0, "amplitudes": amplitudes,
              "log_decrement_per_period": delta, "damping_ratio_from_extrema": zeta_extrema,
              "flux_amplitude": flux_amplitude, "flux_amplitude_expected": flux_expected}
    print(f"U-tube, L = {length:.4g} m, d = {params['LIGGGHTS_SPH_parameters.particlespacing']} m: "
          f"natural period {natural:.4f} s (damped {damped:.4f} s, zeta {zeta:.4f}; fit of a damped sinusoid, "
          f"RMS residual {1000 * fit['rms_residual']:.2f} mm), linear theory 2 pi sqrt(L/2g) = "
          f"{period_theory:.4f} s, error {100 * error:+.2f} %")
    if crossing_period is not None:
        print(f"  cross-check: zero crossings over {whole // 2} whole period(s) give a damped period of "
              f"{crossing_period:.4f} s ({100 * (crossing_period / damped - 1):+.2f} % from the fit's)")
    print(f"  displacement at release {1000 * s0:.2f} mm; amplitudes per half period [mm]: "
          + ", ".join(f"{1000 * a:.2f}" for a in amplitudes))
    print(f"  logarithmic decrement of the extrema {delta:.4f} per period (damping ratio {zeta_extrema:.4f}); "
          f"channel flux amplitude {flux_amplitude:.4g} m^2/s against omega b s0 = {flux_expected:.4g} m^2/s")
    write_analysis(args.run_dir, result)
    if args.tolerance is not None and abs(error) > args.tolerance:
        print(f"FAIL: period error {100 * error:+.2f} % outside +-{100 * args.tolerance:g} %")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
