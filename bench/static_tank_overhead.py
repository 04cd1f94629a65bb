#!/usr/bin/python3
"""Coupling overhead of the static tank, measured in one run of this script:
  1. the coupled run (fsi-run: fsi-server + mpirun fsi-client) for M steps after the scene's
     equilibration, with the wall time split into LIGGGHTS, contact fix, communication and MBD;
  2. the same particles, scripts and equilibration in plain LIGGGHTS (bench_plain_liggghts:
     `fix wall/region/sph` walls instead of the structure), M steps in one `run`.
Prints both and the ratio coupled/plain. Not a pass/fail test.

  bench/static_tank_overhead.py [--scene SCENE] [--np 2] [--steps 2000] [--build build]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default=os.path.join(ROOT, "examples", "static_tank", "static_tank.scene"))
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--equilibration-steps", type=int, default=2000,
                        help="LIGGGHTS-only steps before the measured ones (both runs)")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    args = parser.parse_args()
    bin_dir = os.path.join(args.build, "bin")
    overrides = [f"Resolution.equilibration_steps={args.equilibration_steps}",
                 f"Resolution.end_time={args.steps}*Resolution.time_step",
                 "Resolution.snapshot_every_steps=0"]

    with tempfile.TemporaryDirectory(prefix="fsi_bench_") as folder:
        command = [os.path.join(bin_dir, "fsi-run"), args.scene, "--np", str(args.np), "--output",
                   os.path.join(folder, "coupled")]
        for item in overrides:
            command += ["--set", item]
        subprocess.run(command, env=ENV, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with open(os.path.join(folder, "coupled", "run.json")) as handle:
            run = json.load(handle)

    flat = run["parameters_flat"]
    width, thickness, height = flat["Geometry.width"], flat["Geometry.thickness"], flat["Geometry.height"]
    command = ["mpirun", "--oversubscribe", "--bind-to", "none", "-np", str(args.np)]  # as fsi-run
    if os.geteuid() == 0:
        command.append("--allow-run-as-root")
    command += [os.path.join(bin_dir, "bench_plain_liggghts"), args.scene, "--steps", str(args.steps),
                "--region", "0", str(width), str(0.5 * thickness), str(height)]
    for item in overrides:
        command += ["--set", item]
    output = subprocess.run(command, env=ENV, check=True, capture_output=True, text=True).stdout
    plain = json.loads([line for line in output.splitlines() if line.startswith("{")][-1])

    t = run["timings_seconds"]
    coupled = t["coupled_phase"]
    steps = run["steps"]
    outside = t["contact_fix"] + t["communication"] + t["mbd"] + t["output"]
    print(f"scene {os.path.relpath(args.scene, ROOT)}: {run['fluid']['particle_count']} particles, "
          f"{steps} steps, {args.np} rank(s)")
    print(f"coupled: {coupled:.3f} s = {1e3 * coupled / steps:.3f} ms/step "
          f"(LIGGGHTS {t['liggghts']:.3f} s, contact fix {t['contact_fix']:.3f} s, "
          f"communication {t['communication']:.3f} s, MBD {t['mbd']:.3f} s, output {t['output']:.3f} s)")
    print(f"outside LIGGGHTS' SPH work (fix + communication + MBD + output): {outside:.3f} s = "
          f"{100 * outside / coupled:.1f} % of the coupled wall time")
    print(f"plain LIGGGHTS (wall/region/sph walls): {plain['seconds_loop']:.3f} s = "
          f"{1e3 * plain['seconds_loop'] / plain['steps']:.3f} ms/step")
    print(f"ratio coupled/plain: {coupled / plain['seconds_loop']:.3f}")


if __name__ == "__main__":
    sys.exit(main())
