#!/usr/bin/python3
"""Strong scaling 1 -> 2 ranks, and what the balanced decomposition buys (docs/user-guide.md,
"Ranks and balance"; docs/performance.md, "Ranks and balance").

Cases (`--case`):
  dam_break  Martin & Moyce's column, `--resolution` particles across it (2 r^2 particles; 158:
             49 928); script 1 splits along x, the column stands in the left tenth of the tank.
  box_3d     the 3D hydrostatic box, `--resolution` particles across its 12 mm (h = 1.2 d, dt
             scaled with d; 56: about 10^5 particles), the grid chosen by the client.
All runs in one invocation, on the same particles: coupled (fsi-run) on 1 rank; on 2 ranks
balanced (the default); on 2 ranks with `--balance off` (LIGGGHTS' even cuts: for the dam break,
rank 0 holds the whole column). Prints the coupled phase's wall time per step, the decomposition
lines of the client's log and the speed-ups 2 ranks / 1 rank. Not a pass/fail test; the machine
should be otherwise idle.

The ratio coupled / plain LIGGGHTS is bench/static_tank_overhead.py's (--np 1 and 2): LIGGGHTS'
own wall/region/sph walls, its baseline's walls, let the dam break's particles through at this
resolution ("Particle on or inside fix wall/region/sph surface" within 400 steps).

  bench/balance.py [--case dam_break|box_3d] [--resolution R] [--fill-height H] [--steps 1000]
                   [--equilibration-steps 100] [--runs np1,np2,np2_even] [--plain] [--build build]

--plain also runs the same particles, scripts and equilibration in plain LIGGGHTS (bench_plain_liggghts:
the structure replaced by LIGGGHTS' own `fix wall/region/sph` walls on the tank's inside faces, the
measured steps in one `run`, the ranks pinned like the coupled runs) on the rank counts of --runs, and
prints the ratio coupled/plain of each (issue 17: at most 1.0 asked). The walls' range is one particle
spacing and their prefactor D `--plain-strength` (default 5 for box_3d, 0.2 for dam_break, the values
that hold each fluid): with the scene's wall range (2 h), or D = 1 at 158 columns, LIGGGHTS'
Lennard-Jones-like wall throws the particles that start within it (d/2 from the dam break's walls)
through the wall within 10 steps ("Particle on or inside surface"). `--plain-walls none` leaves the walls out (the cheapest
baseline there is).
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
SCENES = {"dam_break": os.path.join(ROOT, "examples", "dam_break", "martin_moyce.scene"),
          "box_3d": os.path.join(ROOT, "examples", "hydrostatic_box_3d", "hydrostatic_box_3d.scene")}


def case_overrides(case, resolution, steps, equilibration_steps, fill_height=None):
    """(overrides, time step, resolution's description) of a case."""
    if case == "dam_break":
        # dt c / h = 0.092 as in every resolution of the example (dt = 2.5e-5 s at 10 columns).
        time_step = 2.5e-5 * 10 / resolution
        overrides = [f"Resolution.columns={resolution}", f"Resolution.time_step={time_step:.6g}",
                     f"Resolution.equilibration_steps={equilibration_steps}",
                     f"Resolution.end_time={steps}*Resolution.time_step",
                     "Resolution.snapshot_every_steps=0", "Resolution.sensor_every_steps=100"]
        return overrides, time_step, f"{resolution} particles across the column"
    # The example: d = 1 mm (12 across), h = 1.2 d, dt = 2.5e-5 s; all three scale with d.
    spacing = 0.012 / resolution
    time_step = float(f"{2.5e-5 * spacing / 0.001:.6g}")
    prefix = "LIGGGHTS_SPH_parameters."
    overrides = [f"{prefix}particlespacing={spacing:.9g}", f"{prefix}smoothinglength={1.2 * spacing:.9g}",
                 f"SolverOptions.Timeint.step_size={time_step:.9g}",
                 f"LIGGGHTS.equilibration_steps={equilibration_steps}",
                 f"SolverOptions.end_time={steps * time_step:.9g}",
                 "Output.snapshot_every_steps=0", "Output.sensor_every_steps=100",
                 # A timing run: the lattice has not settled after 100 steps (|rho/rho0 - 1| up to
                 # 4.5 % at release), which the health check would stop at its 3 %.
                 "FluidHealth.max_density_deviation=0.1"]
    if fill_height is not None:
        # The example's lattice (h off the side walls, from z = 0.8 mm) filled higher.
        overrides += [f"FluidRegion.lower=[{1.2 * spacing:.9g}, {1.2 * spacing:.9g}, 0.0008]",
                      f"FluidRegion.upper=[{0.012 - 1.2 * spacing:.9g}, {0.012 - 1.2 * spacing:.9g}, "
                      f"{0.0008 + fill_height:.9g}]"]
    return overrides, time_step, f"{resolution} particles across the box (d = {1e3 * spacing:.4g} mm)"


def fsi_run_command(bin_dir, scene, run_dir, ranks, overrides, client_args=(), bind="core"):
    """fsi-run's command line. bind "core" (the default here): a machine given to one run, the
    ranks pinned to their cores (8 % faster than unpinned on 2 ranks, docs/performance.md "Ranks
    and balance"); "none" for runs side by side, which pinned would all share core 0."""
    command = [os.path.join(bin_dir, "fsi-run"), scene, "--np", str(ranks), "--output", run_dir,
               "--bind-to", bind]
    for item in overrides:
        command += ["--set", item]
    for item in client_args:
        command += ["--client-arg", item]
    return command


def coupled(bin_dir, folder, scene, name, ranks, overrides, client_args):
    run_dir = os.path.join(folder, name)
    command = fsi_run_command(bin_dir, scene, run_dir, ranks, overrides, client_args)
    subprocess.run(command, env=ENV, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(run_dir, "run.json")) as handle:
        run = json.load(handle)
    with open(os.path.join(run_dir, "fsi-client.log")) as handle:
        log = handle.read()
    decomposition = [line.split("] ", 3)[-1] for line in log.splitlines() if "decomposition:" in line
                     or "balance:" in line or "memory:" in line or "ghosts:" in line
                     or "boundary:" in line]
    return run, decomposition


def walls_region(case, flat):
    """The block whose faces stand in for the structure in plain LIGGGHTS: the tank's inside."""
    if case == "dam_break":
        return [0.0, flat["Geometry.tank_length"], 0.0, flat["Geometry.wall_height"]]
    return [0.0, flat["Geometry.length"], 0.0, flat["Geometry.length"], 0.0, flat["Geometry.height"]]


def plain(bin_dir, scene, ranks, overrides, steps, region, strength, client_args):
    """Seconds of `steps` plain-LIGGGHTS steps of the scene's particles (bench_plain_liggghts)."""
    command = ["mpirun", "--oversubscribe", "--bind-to", "core", "-np", str(ranks)]
    if os.geteuid() == 0:
        command.append("--allow-run-as-root")
    command += [os.path.join(bin_dir, "bench_plain_liggghts"), scene, "--steps", str(steps)]
    if region:
        command += ["--region"] + [f"{value:.17g}" for value in region] + ["--cutoff", "${particlespacing}",
                                                                          "--strength", f"{strength:g}"]
    else:
        command += ["--walls", "none"]
    if "--balance=off" in client_args:
        command += ["--balance", "off"]
    for item in overrides:
        command += ["--set", item]
    output = subprocess.run(command, env=ENV, check=True, capture_output=True, text=True).stdout
    return json.loads([line for line in output.splitlines() if line.startswith("{")][-1])["seconds_loop"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--case", choices=sorted(SCENES), default="dam_break")
    parser.add_argument("--resolution", type=int, default=None,
                        help="particles across the column (dam_break, default 158) or the box (box_3d, default 56)")
    parser.add_argument("--steps", type=int, default=400, help="coupled steps measured")
    parser.add_argument("--equilibration-steps", type=int, default=100)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--fill-height", type=float, default=None,
                        help="box_3d: height of the water [m] (default: the example's 0.008; 0.017 with "
                             "56 across gives about 2.2e5 particles)")
    parser.add_argument("--runs", default="np1,np2,np2_even",
                        help="which of np1, np2, np2_even to run (default: all three)")
    parser.add_argument("--plain", action="store_true",
                        help="also run plain LIGGGHTS on the same particles and print coupled/plain")
    parser.add_argument("--plain-walls", choices=["region", "none"], default="region",
                        help="the plain runs' walls: LIGGGHTS' wall/region/sph (default) or none")
    parser.add_argument("--plain-strength", type=float, default=None,
                        help="the plain walls' prefactor D (default 5 for box_3d, 0.2 for dam_break)")
    args = parser.parse_args()
    bin_dir = os.path.join(args.build, "bin")
    resolution = args.resolution or (158 if args.case == "dam_break" else 56)
    overrides, time_step, described = case_overrides(args.case, resolution, args.steps, args.equilibration_steps,
                                                     args.fill_height)
    with tempfile.TemporaryDirectory(prefix="fsi_bench_balance_") as folder:
        runs, plains = {}, {}
        for name, ranks, client_args in (("np1", 1, []), ("np2", 2, []), ("np2_even", 2, ["--balance=off"])):
            if name not in args.runs.split(","):
                continue
            runs[name] = coupled(bin_dir, folder, SCENES[args.case], name, ranks, overrides, client_args)
            if args.plain:
                region = (walls_region(args.case, runs[name][0]["parameters_flat"]) if args.plain_walls == "region"
                          else None)
                strength = args.plain_strength or (0.2 if args.case == "dam_break" else 5.0)
                plains[name] = plain(bin_dir, SCENES[args.case], ranks, overrides, runs[name][0]["steps"], region,
                                     strength, client_args)

    particles = next(iter(runs.values()))[0]["fluid"]["particle_count"]
    print(f"{args.case}, {described}: {particles} particles, "
          f"{args.steps} coupled steps after {args.equilibration_steps} of equilibration, dt = {time_step:.4g} s")
    seconds = {}
    for name, (run, decomposition) in runs.items():
        t = run["timings_seconds"]
        seconds[name] = t["coupled_phase"]
        print(f"  coupled {name}: {t['coupled_phase']:.3f} s = {1e3 * t['coupled_phase'] / run['steps']:.3f} ms/step "
              f"(LIGGGHTS {t['liggghts']:.3f} s, contact fix {t['contact_fix']:.3f} s, communication "
              f"{t['communication']:.3f} s, MBD {t['mbd']:.3f} s); equilibration "
              f"{t['client_equilibration']:.3f} s")
        for line in decomposition:
            print(f"      {line}")
        if name in plains:
            print(f"      plain LIGGGHTS, same particles and ranks, walls {args.plain_walls}: {plains[name]:.3f} s = "
                  f"{1e3 * plains[name] / run['steps']:.3f} ms/step; coupled/plain {t['coupled_phase'] / plains[name]:.3f}")
    for name, label in (("np2", "balanced"), ("np2_even", "even cuts")):
        if "np1" in seconds and name in seconds:
            print(f"speed-up 2 ranks / 1 rank, coupled, {label}: {seconds['np1'] / seconds[name]:.3f}")


if __name__ == "__main__":
    sys.exit(main())
