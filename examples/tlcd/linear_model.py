#!/usr/bin/python3
"""The linear TLCD model of the tuning study (README.md, "The tuning study"): the building's top
and the water column as a linear system of three degrees of freedom, pushed and released as the
coupled runs are, and measured as analyze.py measures them.

Coordinates: x the building's tip (the top storey's horizontal displacement), theta the tip's
slope (the top storey, and the tube on it, tilt by theta: its +x leg goes down), u the column's
displacement along the tube (the water rises by u in the +x leg). Lagrange's equations, linear in
all three:

  kinetic    (M_x + m) x'^2/2 + (J + J_w) theta'^2/2 + m h_cm x' theta'
             + m u'^2/2 + alpha m u' (x' + (e_c - h_leg) theta')
  potential  [x theta] K [x theta]^T / 2 + m w_d^2 u^2/2 - alpha m g theta u - m g h_cm theta^2/2

m the water (rho_w (2 b (fill - b) + (D + b) b)), alpha = D/L, L = 2 (fill - b/2) + D the column,
w_d its circular frequency (linear theory's sqrt(2 g / L) raised by what examples/u_tube
measured for our d = 5 mm column at that fill, MEASURED_COLUMN, or by `--column-speedup`), h_leg = fill - b/2 the water's length in a leg,
e_c = b/2 the bottom channel's centre line and h_cm = fill/2 about the water's centre of mass,
both above the tube's floor, J and J_w the top storey's and the water's moments of inertia about
the tip. The column is driven by the tip's acceleration (Sakai's alpha m x''), by the tilt's
angular acceleration (the legs move up and down with it) and by gravity along the tilted tube
(alpha m g theta); the water's weight shifts from leg to leg and bends the building back through
the same term. K is the cantilever's tip stiffness (EI/H^3 [[12, -6H], [-6H, 4H^2]]) less the
geometric stiffness of the weight it carries, scaled so the building with the water lumped on its
top swings with the period the tuning study's --mbd-only runs measured (LUMPED_PERIOD, or
`--tuning DIR` to read them); M_x = the top storey plus the cantilever's modal share of its mass;
the building's 1.2 % damping on x, the column's 2 zeta_d w_d m (zeta_d as measured in the U-tube,
MEASURED_COLUMN, or as given by --column-damping). `--no-tilt` drops theta: Sakai's equations of a column on a structure that only
translates.

The push rises linearly to 150 N/m over 2 s from rest and is removed (the scene's); the response is
integrated exactly (matrix exponential of the system with time as a state) and measured from the
release: the positive extrema of x, the logarithmic decrement over the first four periods.

  linear_model.py [--column-damping measured,0.06,0.10] [--column-speedup 0.018] [--no-tilt]
                  [--fills 0.08,...] [--tuning out/tlcd_tuning]"""
import argparse
import json
import math
import os

import numpy as np

G = 9.81
B = 0.04
D = 0.30
H = 2.0
BENDING_STIFFNESS = 3.1e4
TOP_MASS = 230.0
TOP_WIDTH = D + B
BEAM_MASS = 20.0 * H
MODAL_MASS = TOP_MASS + 0.236 * BEAM_MASS   # top storey + the cantilever's modal share of its mass
BUILDING_DAMPING = 0.012                    # the empty building's, measured (README.md)
PUSH, RELEASE, END = 150.0, 2.0, 9.0
# The building's period with each fill's water lumped on its top (tuning.py's --mbd-only runs,
# 2026-12-04/05); fills between them are interpolated (the period is linear in the fill to 1e-4 s).
LUMPED_PERIOD = {0.08: 1.0038, 0.11: 1.0088, 0.125: 1.0125, 0.14: 1.0150, 0.155: 1.0169, 0.17: 1.0200, 0.185: 1.0222,
                 0.20: 1.0250}
# The column in our SPH fluid, measured in examples/u_tube at d = 5 mm with the TLCD's c and step
# for each fill (column.py, 2026-12-05): its natural frequency above linear theory's
# (1 / (1 + period error) - 1) and its damping ratio (fit of a damped sinusoid, 25 mm).
MEASURED_COLUMN = {0.11: (0.0229, 0.0761), 0.14: (0.0199, 0.0945), 0.17: (0.0123, 0.1128), 0.20: (0.0126, 0.1365)}


def expm(matrix):
    """The matrix exponential by scaling and squaring a Taylor series (numpy alone; 18 terms after
    scaling to a norm below 1/2 are exact to rounding)."""
    norm = np.linalg.norm(matrix, 1)
    squarings = max(0, int(math.ceil(math.log2(norm / 0.5)))) if norm > 0.5 else 0
    scaled = matrix / 2.0 ** squarings
    result, term = np.eye(len(matrix)), np.eye(len(matrix))
    for k in range(1, 19):
        term = term @ scaled / k
        result = result + term
    for _ in range(squarings):
        result = result @ result
    return result


def fill_levels(parser, text):
    """The fill levels of a --fills value (metres, comma-separated), or the parser's error."""
    try:
        return [float(v) for v in text.split(",")]
    except ValueError:
        parser.error(f"--fills {text!r}: give fill levels in metres separated by commas, e.g. 0.11,0.14,0.17")


def lumped_period(fill, table):
    fills = sorted(table)
    return float(np.interp(fill, fills, [table[f] for f in fills]))


def matrices(fill, zeta_d, speedup, period, tilt):
    """Mass, damping and stiffness matrices over (x, theta, u) (over (x, u) without the tilt)."""
    length = 2 * (fill - B / 2) + D
    water = 1000.0 * (2 * B * (fill - B) + (D + B) * B)
    alpha = D / length
    w_d = math.sqrt(2 * G / length) * (1 + speedup)
    h_leg, e_c, h_cm = fill - B / 2, B / 2, fill / 2
    inertia = TOP_MASS * TOP_WIDTH ** 2 / 12
    inertia_water = water * (TOP_WIDTH ** 2 / 12 + h_cm ** 2)
    cantilever = BENDING_STIFFNESS / H ** 3 * np.array([[12.0, -6 * H], [-6 * H, 4 * H * H]])
    load = (TOP_MASS + water + BEAM_MASS / 2) * G
    geometric = load / (30 * H) * np.array([[36.0, -3 * H], [-3 * H, 4 * H * H]])
    building = cantilever - geometric
    # Scale the building's stiffness to the measured period with the water lumped on its top (the
    # --mbd-only run: the water's mass on the top node, its inertia as the scene's top_inertia).
    lumped = np.diag([MODAL_MASS + water, inertia + water * TOP_WIDTH ** 2 / 12])
    omega = 2 * math.pi / period
    building *= omega ** 2 / min(np.linalg.eigvals(np.linalg.solve(lumped, building)).real)
    c_x = 2 * BUILDING_DAMPING * omega * (MODAL_MASS + water)
    if not tilt:
        k = (MODAL_MASS + water) * omega ** 2
        mass = np.array([[MODAL_MASS + water, alpha * water], [alpha * water, water]])
        return mass, np.diag([c_x, 2 * zeta_d * w_d * water]), np.diag([k, water * w_d ** 2]), w_d
    mass = np.array([[MODAL_MASS + water, water * h_cm, alpha * water],
                     [water * h_cm, inertia + inertia_water, alpha * water * (e_c - h_leg)],
                     [alpha * water, alpha * water * (e_c - h_leg), water]])
    stiffness = np.zeros((3, 3))
    stiffness[:2, :2] = building
    stiffness[1, 1] -= water * G * h_cm
    stiffness[1, 2] = stiffness[2, 1] = -alpha * water * G
    stiffness[2, 2] = water * w_d ** 2
    return mass, np.diag([c_x, 0.0, 2 * zeta_d * w_d * water]), stiffness, w_d


def response(mass, damping, stiffness, dt=1e-3):
    """x(t) from rest under the scene's push, sampled every dt from the release to END."""
    n = len(mass)
    inverse = np.linalg.inv(mass)
    # State (q, q', t, 1): the push PUSH t / RELEASE on x is linear in the state while it acts.
    def system(pushing):
        a = np.zeros((2 * n + 2, 2 * n + 2))
        a[:n, n:2 * n] = np.eye(n)
        a[n:2 * n, :n] = -inverse @ stiffness
        a[n:2 * n, n:2 * n] = -inverse @ damping
        a[2 * n, 2 * n + 1] = 1.0
        if pushing:
            a[n:2 * n, 2 * n] = inverse[:, 0] * PUSH / RELEASE
        return a
    state = np.zeros(2 * n + 2)
    state[-1] = 1.0
    state = expm(system(True) * RELEASE) @ state
    step = expm(system(False) * dt)
    x = []
    for _ in range(int(round((END - RELEASE) / dt))):
        x.append(state[0])
        state = step @ state
    return np.array(x)


def damping_ratios(x, cycles=4):
    """analyze.py's measures: the largest x of each positive lobe after the release (the first lobe
    starts at the release); the logarithmic decrement over `cycles` periods and the least-squares
    slope of ln a_i over the same extrema, each as a damping ratio."""
    peaks, best, positive = [], x[0], True
    for value in x[1:]:
        if positive and value <= 0:
            peaks.append(best)
            positive = False
        elif not positive and value > 0:
            positive, best = True, value
        if positive:
            best = max(best, value)
    delta = math.log(peaks[0] / peaks[cycles]) / cycles
    slope = -np.polyfit(np.arange(cycles + 1), np.log(peaks[:cycles + 1]), 1)[0]
    return tuple(v / math.sqrt(4 * math.pi ** 2 + v ** 2) for v in (delta, slope))


def measured_column(fill):
    """(frequency above linear theory, damping ratio) of the column at `fill`, interpolated in
    MEASURED_COLUMN (held at the ends)."""
    fills = sorted(MEASURED_COLUMN)
    return tuple(float(np.interp(fill, fills, [MEASURED_COLUMN[f][i] for f in fills])) for i in (0, 1))


def model_damping(fill, zeta_d=None, speedup=None, table=None, tilt=True):
    """(damping ratio by the decrement, by least squares, column/building frequency ratio) of the
    model at `fill` with the column's damping ratio `zeta_d` and frequency `speedup` above linear
    theory (None: the measured column's)."""
    measured = measured_column(fill)
    speedup = measured[0] if speedup is None else speedup
    zeta_d = measured[1] if zeta_d is None else zeta_d
    period = lumped_period(fill, table or LUMPED_PERIOD)
    mass, damping, stiffness, w_d = matrices(fill, zeta_d, speedup, period, tilt)
    return (*damping_ratios(response(mass, damping, stiffness)), w_d * period / (2 * math.pi))


def read_tuning(folder):
    """The lumped periods measured by tuning.py in `folder` (fill_<f>/lumped/analysis.json)."""
    table = {}
    for name in os.listdir(folder):
        path = os.path.join(folder, name, "lumped", "analysis.json")
        if name.startswith("fill_") and os.path.exists(path):
            with open(path) as handle:
                table[float(name[5:])] = json.load(handle)["period"]
    if not table:
        raise SystemExit(f"linear_model.py: no fill_<f>/lumped/analysis.json in {folder}; run tuning.py first")
    return table


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--column-damping", default="measured,0.06,0.10",
                        help="the column's damping ratios, comma-separated; 'measured': MEASURED_COLUMN's")
    parser.add_argument("--column-speedup", type=float,
                        help="the column's frequency above linear theory (default: MEASURED_COLUMN's, 1.2-2.3 %%)")
    parser.add_argument("--no-tilt", action="store_true", help="the building's top translates only (Sakai)")
    parser.add_argument("--fills", default="0.08,0.11,0.125,0.14,0.155,0.17,0.185,0.20")
    parser.add_argument("--tuning", help="tuning.py's output folder: its measured lumped periods")
    args = parser.parse_args()
    dampings = [None if v == "measured" else float(v) for v in args.column_damping.split(",")]
    fills = fill_levels(parser, args.fills)
    table = read_tuning(args.tuning) if args.tuning else LUMPED_PERIOD
    print(("translating" if args.no_tilt else "translating and tilting") + " building; damping ratio by the "
          "logarithmic decrement over 4 periods (least squares over the same extrema)")
    print("fill [m]  frequency ratio  " + "  ".join(f"zeta (column {z if z is not None else 'measured'})" for z in dampings))
    best = {z: (0.0, None) for z in dampings}
    for fill in fills:
        row = []
        for zeta_d in dampings:
            zeta, zeta_fit, ratio = model_damping(fill, zeta_d, args.column_speedup, table, not args.no_tilt)
            best[zeta_d] = max(best[zeta_d], (zeta, fill))
            row.append(f"{zeta:.4f} ({zeta_fit:.4f})")
        print(f"{fill:7.3f}  {ratio:15.3f}  " + "  ".join(f"{v:>18}" for v in row))
    for zeta_d, (zeta, fill) in best.items():
        print(f"column damping {zeta_d if zeta_d is not None else 'measured'}: the most damping (decrement) at fill {fill:g} m (zeta {zeta:.4f})")


if __name__ == "__main__":
    main()
