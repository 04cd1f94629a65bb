#!/usr/bin/python3
"""Evaluates a static tank run (thesis §6.3) from DIR/sensors.csv and DIR/run.json.

Prints and writes DIR/analysis.json with
  - weight consistency: time-averaged fluid force on the bottom over the settled interval before
    the piston touches the fluid, against the exact weight N*m*g (thesis eq. 6.8-6.11);
  - constraint-force consistency: the fluid force recovered from the Lagrange multipliers of the
    bottom's constraints (minus the bottom's own weight) against the summed vertex forces, at
    every step;
  - volume consistency: the effective fluid volume from the onset of compression by the piston,
    V = (h0 - 2h)(b - 2h) (thesis eq. 6.5-6.6), against N*m/rho0; with --true-shape (the
    true-shape wall, static_tank_true_shape*.scene) V = h0 b, without the thesis' correction.
    Both figures are printed either way.
Exit status 1 if a tolerance given on the command line is not met.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import fluid_weight, read_run, weight_check_arguments, write_analysis  # noqa: E402 (examples/fsi_results.py)


def find_block(tree, name):
    for entry in tree.get("entries", []):
        if entry.get("kind") == "block" and entry.get("name") == name:
            return entry
    raise KeyError(name)


def main():
    parser = weight_check_arguments(__doc__, 0.05, "default 0.05")
    parser.add_argument("--contact-margin", type=float, default=0.02,
                        help="the interval ends this long before the piston touches [s]")
    parser.add_argument("--lambda-tolerance", type=float,
                        help="fail if the multiplier-based force differs by more (relative)")
    parser.add_argument("--volume-tolerance", type=float, help="fail if |V/V_exact - 1| exceeds this")
    parser.add_argument("--true-shape", action="store_true",
                        help="judge V = h0 b (the true-shape wall) instead of (h0 - 2h)(b - 2h)")
    args = parser.parse_args()

    run, sensors = read_run(args.run_dir)
    n = run["fluid"]["particle_count"]
    m, g, weight = fluid_weight(run, n)
    rho0 = run["fluid"]["density"]
    gravity = run["model"]["gravity"]
    bodies = {body["name"]: body for body in run["model"]["bodies"]}
    bottom_mass = bodies["bottom"]["mass"]
    params = run["parameters_flat"]
    h = params["LIGGGHTS_SPH_parameters.smoothinglength"]
    width = params["Geometry.width"]
    thickness = params["Geometry.thickness"]

    time = sensors["time"]
    bottom = sensors["bottom_fluid_force_y"]
    constraint = sensors["bottom_constraint_force_y"]
    piston_force = sensors["piston_fluid_force_y"]
    piston_y = sensors["piston_position_y"]

    # Onset of compression: the piston carries the full fluid weight for the first time.
    contact_index = next((i for i, f in enumerate(piston_force) if f >= weight), None)
    t_contact = time[contact_index] if contact_index is not None else None
    t_end = (t_contact - args.contact_margin) if t_contact is not None else time[-1]
    window = [i for i, t in enumerate(time) if args.settle_start <= t <= t_end]
    if len(window) < 10:
        print(f"analyze: only {len(window)} samples in the settled interval "
              f"[{args.settle_start}, {t_end}] s; run longer", file=sys.stderr)
        return 1
    mean_force = sum(bottom[i] for i in window) / len(window)
    weight_ratio = -mean_force / weight

    # Equilibrium of the held bottom: F_fluid + m_b g_y + F_constraint = 0.
    worst = 0.0
    worst_time = None
    for t, fluid_force, constraint_force in zip(time, bottom, constraint):
        from_multipliers = -constraint_force - bottom_mass * gravity[1]
        scale = max(abs(fluid_force), 1e-6 * weight)
        error = abs(from_multipliers - fluid_force) / scale
        if error > worst:
            worst, worst_time = error, t

    result = {
        "particle_count": n, "particle_mass": m, "exact_weight": weight,
        "settled_interval": [args.settle_start, t_end], "samples": len(window),
        "mean_bottom_fluid_force_y": mean_force, "weight_ratio": weight_ratio,
        "weight_error": weight_ratio - 1.0,
        "max_multiplier_force_relative_error": worst, "at_time": worst_time,
    }
    print(f"particles N = {n}, particle mass m = {m:.6g} kg/m, exact weight N m g = {weight:.6g} N/m")
    print(f"settled interval {args.settle_start:.3f} .. {t_end:.4f} s ({len(window)} samples): "
          f"mean fluid force on the bottom = {-mean_force:.6g} N/m, ratio to N m g = {weight_ratio:.5f}")
    print(f"fluid force from the Lagrange multipliers vs summed vertex forces: max relative "
          f"difference {worst:.3e} over {len(time)} steps")
    failed = False
    if args.weight_tolerance is not None and abs(weight_ratio - 1.0) > args.weight_tolerance:
        print(f"FAIL: weight ratio {weight_ratio:.5f} outside 1 +- {args.weight_tolerance}")
        failed = True
    if args.lambda_tolerance is not None and worst > args.lambda_tolerance:
        print(f"FAIL: multiplier-based force differs by {worst:.3e} > {args.lambda_tolerance}")
        failed = True

    if t_contact is not None:
        piston_bottom = piston_y[contact_index] - 0.5 * thickness
        h0 = piston_bottom - 0.5 * thickness  # bottom surface of the fluid at y = thickness/2
        thesis_volume = (h0 - 2 * h) * (width - 2 * h)
        true_volume = h0 * width
        volume = true_volume if args.true_shape else thesis_volume
        exact_volume = n * m / rho0
        result.update({"contact_time": t_contact, "filling_height_h0": h0,
                       "effective_volume": volume, "exact_volume": exact_volume,
                       "volume_ratio": volume / exact_volume,
                       "volume_ratio_thesis_correction": thesis_volume / exact_volume,
                       "volume_ratio_without_correction": true_volume / exact_volume})
        print(f"onset of compression t_c = {t_contact:.5f} s, filling height h0 = {h0:.6g} m, "
              f"N m/rho0 = {exact_volume:.6g} m^2: V = (h0-2h)(b-2h) = {thesis_volume:.6g} m^2, ratio "
              f"{thesis_volume / exact_volume:.5f}; V = h0 b = {true_volume:.6g} m^2, ratio "
              f"{true_volume / exact_volume:.5f}; judged: {'h0 b' if args.true_shape else '(h0-2h)(b-2h)'}")
        if args.volume_tolerance is not None and abs(volume / exact_volume - 1) > args.volume_tolerance:
            print(f"FAIL: volume ratio outside 1 +- {args.volume_tolerance}")
            failed = True
    else:
        print("the piston did not reach the fluid in this run: no volume measurement")
        if args.volume_tolerance is not None:
            print("FAIL: a volume tolerance was given but the piston never compressed the fluid")
            failed = True

    write_analysis(args.run_dir, result)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
