#!/usr/bin/python3
"""Channel flows against the series solutions of Morris, Fox & Zhu (1997), J. Comput. Phys. 136.

Reads DIR/sensors.csv (the point probes u1..u7 at y = k L/8, midway along the period) and prints:
- the profile error at the Morris times 0.0225, 0.045, 0.1125, 0.225 s (and the last row): the
  largest |u_sim - u_series| over the probes, relative to the peak velocity (Poiseuille
  F L^2/(8 nu), Couette v0);
- the centre velocity at the last row against the series value at that time (Poiseuille: the
  steady F L^2/(8 nu) once t >> L^2/(pi^2 nu) = 0.1 s);
- what the flow says about the fluid and the walls: the viscosity nu_fit that best fits every
  row to the series (least squares), and, from a parabola (Poiseuille) or line (Couette) through
  the last row, the effective viscosity -F/u'' and the positions where the fitted profile meets
  the walls' velocity (the effective no-slip walls, in units of the spacing d).
Exits 1 when a profile error exceeds --profile-tolerance or the centre error --centre-tolerance.

With --plot, DIR/profiles.png shows the probes' profiles against the series at the checked times.

Usage: analyze.py DIR --flow poiseuille|couette [--profile-tolerance 0.05]
                  [--centre-tolerance 0.03] [--particles-across N] [--plot]"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import fsi_results  # noqa: E402

# Morris et al. (1997), section 4.1-4.2.
L = 1e-3
NU = 1e-6
F = 2e-4
V0 = 2.5e-5
MORRIS_TIMES = [0.0225, 0.045, 0.1125, 0.225]
PROBES = [f"u{k}" for k in range(1, 8)]
PROBE_Y = [k * L / 8 for k in range(1, 8)]


def poiseuille(y, t, nu=NU, terms=200):
    """u(y, t) from rest under the body force F, walls at y = 0 and L (no slip)."""
    u = F / (2 * nu) * y * (L - y)
    for n in range(terms):
        m = 2 * n + 1
        u -= (4 * F * L * L / (nu * math.pi ** 3 * m ** 3) * math.sin(m * math.pi * y / L)
              * math.exp(-m * m * math.pi ** 2 * nu * t / (L * L)))
    return u


def couette(y, t, nu=NU, terms=400):
    """u(y, t) from rest, the wall at y = L moving at V0 from t = 0 on, the one at y = 0 at rest."""
    u = V0 * y / L
    for n in range(1, terms + 1):
        u += (2 * V0 / (n * math.pi) * (-1) ** n * math.sin(n * math.pi * y / L)
              * math.exp(-n * n * math.pi ** 2 * nu * t / (L * L)))
    return u


def row_at(times, t):
    best = min(range(len(times)), key=lambda i: abs(times[i] - t))
    return best if abs(times[best] - t) < 1e-6 else None


def polyfit(xs, ys, degree):
    """Least-squares polynomial coefficients c0 + c1 x + ... (normal equations; few points)."""
    n = degree + 1
    a = [[sum(x ** (i + j) for x in xs) for j in range(n)] for i in range(n)]
    b = [sum(y * x ** i for x, y in zip(xs, ys)) for i in range(n)]
    for col in range(n):
        pivot = max(range(col, n), key=lambda r: abs(a[r][col]))
        a[col], a[pivot] = a[pivot], a[col]
        b[col], b[pivot] = b[pivot], b[col]
        for r in range(n):
            if r != col:
                factor = a[r][col] / a[col][col]
                a[r] = [ar - factor * ac for ar, ac in zip(a[r], a[col])]
                b[r] -= factor * b[col]
    return [b[i] / a[i][i] for i in range(n)]


def fit_viscosity(exact, times, columns):
    """The nu minimising the squared profile error over every row (golden section on log nu)."""
    def cost(log_nu):
        nu = math.exp(log_nu)
        return sum((columns[p][i] - exact(y, times[i], nu)) ** 2
                   for p, y in zip(PROBES, PROBE_Y) for i in range(0, len(times), 4) if times[i] > 0)
    lo, hi = math.log(NU / 10), math.log(NU * 10)
    g = (math.sqrt(5) - 1) / 2
    for _ in range(60):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if cost(a) < cost(b):
            hi = b
        else:
            lo = a
    return math.exp(0.5 * (lo + hi))


def plot(run_dir, flow, exact, times, columns, checked):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(figsize=(6, 4.5))
    fine = [L * k / 200 for k in range(201)]
    for n, t in enumerate(checked):
        i = row_at(times, t)
        colour = f"C{n}"
        axes.plot([exact(y, times[i]) * 1e6 for y in fine], [y * 1e3 for y in fine], color=colour,
                  label=f"t = {times[i]:.4g} s")
        axes.plot([columns[p][i] * 1e6 for p in PROBES], [y * 1e3 for y in PROBE_Y], "o", color=colour)
    axes.set_xlabel("u [1e-6 m/s]")
    axes.set_ylabel("y [mm]")
    axes.set_title(f"{flow.capitalize()}: SPH (points), series of Morris et al. 1997 (lines)", fontsize=10)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(os.path.join(run_dir, "profiles.png"), dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--flow", choices=["poiseuille", "couette"], required=True)
    parser.add_argument("--profile-tolerance", type=float, default=0.05)
    parser.add_argument("--centre-tolerance", type=float, default=0.03)
    parser.add_argument("--particles-across", type=int, default=0,
                        help="N = L/d, to state the effective walls in spacings")
    parser.add_argument("--plot", action="store_true", help="write DIR/profiles.png")
    args = parser.parse_args()
    _, sensors = fsi_results.read_run(args.run_dir)
    times = sensors["time"]
    columns = {p: sensors[p + "_vx"] for p in PROBES}
    poiseuille_flow = args.flow == "poiseuille"
    exact = poiseuille if poiseuille_flow else couette
    peak = F * L * L / (8 * NU) if poiseuille_flow else V0
    result = {"flow": args.flow, "peak_velocity": peak, "profiles": []}
    failed = False
    checked = [t for t in MORRIS_TIMES if t <= times[-1] + 1e-9] + [times[-1]]
    for t in checked:
        i = row_at(times, t)
        if i is None:
            print(f"no sensors.csv row at t = {t} s")
            return 1
        errors = [columns[p][i] - exact(y, times[i]) for p, y in zip(PROBES, PROBE_Y)]
        worst = max(abs(e) for e in errors) / peak
        failed |= worst > args.profile_tolerance
        print(f"t = {times[i]:.4f} s: " + " ".join(f"{columns[p][i] * 1e6:7.3f}" for p in PROBES)
              + "  (1e-6 m/s, y = L/8 .. 7L/8)")
        print(f"   series     " + " ".join(f"{exact(y, times[i]) * 1e6:7.3f}" for y in PROBE_Y)
              + f"  -> max error {100 * worst:.2f} % of the peak {peak:.3g} m/s")
        result["profiles"].append({"time": times[i], "max_error_over_peak": worst})
    last = len(times) - 1
    centre = columns["u4"][last]
    centre_exact = exact(L / 2, times[last])
    centre_error = (centre - centre_exact) / centre_exact
    failed |= abs(centre_error) > args.centre_tolerance
    print(f"centre velocity at t = {times[last]:.4f} s: {centre:.5g} m/s, series {centre_exact:.5g} "
          f"(steady {exact(L / 2, 1e9):.5g}): {100 * centre_error:+.2f} %")
    result["centre_error"] = centre_error
    nu_fit = fit_viscosity(exact, times, columns)
    result["nu_fit"] = nu_fit
    print(f"viscosity fitting every row: nu = {nu_fit:.4g} m^2/s ({nu_fit / NU:.3f} nu)")
    profile = [columns[p][last] for p in PROBES]
    scale = args.particles_across / L if args.particles_across else None
    if poiseuille_flow:
        c0, c1, c2 = polyfit(PROBE_Y, profile, 2)
        nu_curvature = -F / (2 * c2)
        disc = math.sqrt(c1 * c1 - 4 * c2 * c0)
        walls = sorted([(-c1 + disc) / (2 * c2), (-c1 - disc) / (2 * c2)])
        result["nu_curvature"] = nu_curvature
        print(f"parabola through the last row: nu = -F/u'' = {nu_curvature:.4g} m^2/s "
              f"({nu_curvature / NU:.3f} nu); u = 0 at y = {walls[0]:.4g} and {walls[1]:.4g} m")
    else:
        c0, c1 = polyfit(PROBE_Y, profile, 1)
        walls = [-c0 / c1, (V0 - c0) / c1]
        print(f"line through the last row: u = 0 at y = {walls[0]:.4g} m, u = v0 at y = {walls[1]:.4g} m")
    result["effective_walls"] = walls
    if scale:
        shift = [walls[0] * scale, (L - walls[1]) * scale]
        result["effective_wall_inset_in_spacings"] = shift
        print(f"effective no-slip walls {shift[0]:+.3f} d and {shift[1]:+.3f} d inside the meshes "
              f"(negative: outside)")
    fsi_results.write_analysis(args.run_dir, result)
    if args.plot:
        plot(args.run_dir, args.flow, exact, times, columns, checked)
    print("FAILED" if failed else "passed", f"(profile tolerance {args.profile_tolerance:.0%} of the peak, "
          f"centre {args.centre_tolerance:.0%})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
