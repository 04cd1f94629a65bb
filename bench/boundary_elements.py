#!/usr/bin/python3
"""What a boundary element costs each rank: memory and time per step against the number of mesh
triangles (docs/performance.md, "Cost model"; issue 17 items 2 and 7).

The 3D hydrostatic box (examples/hydrostatic_box_3d, 648 particles) with its container drawn as
12 triangles and as the same box with every face cut into n x n squares
(`make_box_stl.py --subdivide n`: 12 n^2 triangles), coupled on 1 and on 2 ranks. Printed per
run: the coupled phase per step, the contact fix's part, every rank's peak resident memory; then
the memory and the contact time per triangle from the differences to the 12-triangle run, and the
triangles each rank held with the bytes of its share (its part of the mesh plus the halo:
fsi-client's `boundary mesh:` line; rank 0 keeps the whole mesh besides, as the coupling's root). Not a pass/fail test; the machine
should be otherwise idle.

  bench/boundary_elements.py [--subdivisions 1,16,48] [--steps 200] [--resolution R] [--build build]

--resolution R runs the box with R particles across its 12 mm instead of the example's 12 (h, dt and
the spacing scaled as bench/balance.py's box_3d case, 300 settling steps): with fine particles the
halo (the wall's range plus twice the margin, 3 x 2.4 d) is a small part of the box and a rank's
share visibly less than the whole mesh.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "examples", "hydrostatic_box_3d")
TIME_STEP = 2.5e-5  # the example's SolverOptions.Timeint.step_size [s]

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import balance  # noqa: E402  (fsi-run's command line and environment)


def run(bin_dir, folder, parts, ranks, steps, resolution):
    """One coupled run of the example with its box cut `parts` times per face edge."""
    case = os.path.join(folder, f"case_{parts}")
    if not os.path.isdir(case):
        shutil.copytree(EXAMPLE, case)
        with open(os.path.join(case, "box.stl"), "w") as handle:
            subprocess.run([sys.executable, os.path.join(EXAMPLE, "make_box_stl.py"), "--subdivide", str(parts)],
                           stdout=handle, check=True)
    run_dir = os.path.join(folder, f"run_{parts}_np{ranks}")
    if resolution:
        overrides = balance.case_overrides("box_3d", resolution, steps, 300)[0]
    else:
        overrides = [f"SolverOptions.end_time={steps * TIME_STEP:.9g}", "Output.snapshot_every_steps=0"]
    command = balance.fsi_run_command(bin_dir, os.path.join(case, "hydrostatic_box_3d.scene"), run_dir, ranks,
                                      overrides, bind="none")
    subprocess.run(command, env=balance.ENV, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(run_dir, "run.json")) as handle:
        result = json.load(handle)
    with open(os.path.join(run_dir, "fsi-client.log")) as handle:
        log = handle.read()
    memory = re.search(r"memory: peak resident ([\d. /]+) MiB per rank", log)
    held = re.search(r"boundary mesh: [\d /]+ of \d+ elements held per rank at the end \(at most ([\d /]+);", log)
    kib = re.search(r"the shares take ([\d. /]+) KiB per rank, rank 0 keeps the whole mesh besides \(([\d.]+) KiB\)",
                    log)
    t = result["timings_seconds"]
    return {"triangles": 12 * parts * parts, "ranks": ranks, "steps": result["steps"],
            "particles": result["checks"]["particles_initial"],
            "step_ms": 1e3 * t["coupled_phase"] / result["steps"],
            "contact_ms": 1e3 * t["contact_fix"] / result["steps"],
            "memory_mib": [float(v) for v in memory.group(1).split("/")] if memory else [],
            "held": [int(v) for v in held.group(1).split("/")] if held else [],
            "share_kib": [float(v) for v in kib.group(1).split("/")] if kib else [],
            "whole_kib": float(kib.group(2)) if kib else float("nan")}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--subdivisions", default="1,16,48",
                        help="squares per face edge, comma-separated, the first the reference (default 1,16,48)")
    parser.add_argument("--steps", type=int, default=200, help="coupled steps per run")
    parser.add_argument("--resolution", type=int, default=0,
                        help="particles across the 12 mm box (default: the example's 12)")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    args = parser.parse_args()
    parts_list = [int(p) for p in args.subdivisions.split(",")]
    if not parts_list or min(parts_list) < 1:
        parser.error("--subdivisions: whole numbers >= 1")
    if args.resolution < 0:
        parser.error("--resolution: a whole number >= 1 (particles across the box)")
    bin_dir = os.path.join(args.build, "bin")
    results = []
    with tempfile.TemporaryDirectory(prefix="fsi_bench_boundary_") as folder:
        for parts in parts_list:
            for ranks in (1, 2):
                results.append(run(bin_dir, folder, parts, ranks, args.steps, args.resolution))
    print(f"3D hydrostatic box, {results[0]['particles']} particles, {args.steps} coupled steps; the container as "
          f"12 n^2 triangles")
    print("| triangles | ranks | ms/step | contact fix ms/step | peak resident MiB per rank | triangles held per rank "
          "| share KiB per rank | rank 0's whole mesh KiB |")
    print("|---|---|---|---|---|---|---|---|")
    for r in results:
        print(f"| {r['triangles']} | {r['ranks']} | {r['step_ms']:.3f} | {r['contact_ms']:.3f} | "
              f"{' / '.join(f'{m:.1f}' for m in r['memory_mib'])} | {' / '.join(str(h) for h in r['held'])} | "
              f"{' / '.join(f'{k:.1f}' for k in r['share_kib'])} | {r['whole_kib']:.1f} |")
    for ranks in (1, 2):
        same = [r for r in results if r["ranks"] == ranks]
        base = same[0]
        for r in same[1:]:
            extra = r["triangles"] - base["triangles"]
            if extra <= 0 or not r["memory_mib"] or not base["memory_mib"]:
                continue
            per_rank_kib = [1024 * (m - b) / extra for m, b in zip(r["memory_mib"], base["memory_mib"])]
            print(f"{ranks} rank(s), {r['triangles']} triangles against {base['triangles']}: "
                  f"{' / '.join(f'{k:.2f}' for k in per_rank_kib)} KiB per triangle per rank, contact fix "
                  f"{1e3 * (r['contact_ms'] - base['contact_ms']) / extra:.3f} us per triangle per step")
    return 0


if __name__ == "__main__":
    sys.exit(main())
