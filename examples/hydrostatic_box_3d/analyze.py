#!/usr/bin/python3
"""Evaluates a hydrostatic_box_3d run from DIR/sensors.csv and DIR/run.json.

Prints and writes DIR/analysis.json with the time average of the fluid force on the container
along z over the settled interval (from --settle-start to the end), against the fluid weight
N m g (N particles of mass m = rho0 d^3, g = |Gravity.acceleration|), and the particle counts.
The force on the structure points down (-z): the ratio is -F_z / (N m g).
With the held container (hydrostatic_box_3d_held.scene: columns mount_force_z, fluid_force_z) it
also checks the joint: at every row the joint's force from the Lagrange multipliers equals the
container's weight plus the fluid force on it, relative to the fluid weight (--lambda-tolerance).
Exit status 1 if --weight-tolerance is given and |ratio - 1| exceeds it, if particles were lost,
or if the joint check exceeds --lambda-tolerance.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import fluid_weight, read_run, weight_check_arguments, write_analysis  # noqa: E402 (examples/fsi_results.py)


def main():
    parser = weight_check_arguments(__doc__, None, "default: half the end time")
    parser.add_argument("--lambda-tolerance", type=float, default=1e-9,
                        help="held container: fail if |joint - m g + F| / W exceeds this")
    args = parser.parse_args()

    run, sensors = read_run(args.run_dir)
    checks = run["checks"]
    n = checks["particles_final"]
    m, g, weight = fluid_weight(run, n)
    time = sensors["time"]
    start = args.settle_start if args.settle_start is not None else 0.5 * run["end_time"]
    settled = [f for t, f in zip(time, sensors["total_fluid_force_z"]) if t >= start]
    if not settled:
        print("no sensor rows after t = %g s" % start)
        return 1
    force = -sum(settled) / len(settled)
    ratio = force / weight
    lost = checks["particles_initial"] - checks["particles_final"]
    result = {"dimension": run.get("dimension"), "particles_initial": checks["particles_initial"],
              "particles_final": n, "particles_lost": lost, "particle_mass": m, "gravity": g,
              "weight": weight, "settle_start": start, "samples": len(settled),
              "mean_force_z": -force, "weight_ratio": ratio,
              "wall_time_seconds": run["timings_seconds"]["total"]}
    write_analysis(args.run_dir, result)
    print("particles: %d initial, %d final (%d lost)" % (checks["particles_initial"], n, lost))
    print("weight N m g = %d x %.6g kg x %.4g m/s^2 = %.6g N" % (n, m, g, weight))
    print("mean fluid force on the container along z over t >= %.4g s (%d samples): %.6g N"
          % (start, len(settled), -force))
    print("ratio -F_z / (N m g) = %.4f" % ratio)
    failed = False
    if "mount_force_z" in sensors:
        container = run["model"]["bodies"][0]["mass"]
        worst = max(abs(j - container * g + f) for j, f in
                    zip(sensors["mount_force_z"], sensors["fluid_force_z"])) / weight
        result["joint_balance_relative"] = worst
        write_analysis(args.run_dir, result)
        print("joint: |mount force - m_container g + fluid force| / (N m g) <= %.2e over %d rows"
              % (worst, len(sensors["mount_force_z"])))
        if worst > args.lambda_tolerance:
            print("FAIL: the joint check %.2e exceeds %.2e" % (worst, args.lambda_tolerance))
            failed = True
    if lost > 0:
        print("FAIL: %d particle(s) lost" % lost)
        failed = True
    if args.weight_tolerance is not None and abs(ratio - 1.0) > args.weight_tolerance:
        print("FAIL: |ratio - 1| = %.4f exceeds %.4f" % (abs(ratio - 1.0), args.weight_tolerance))
        failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
