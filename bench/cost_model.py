#!/usr/bin/python3
"""A cost model of the coupled step, fitted to 1-rank runs and checked against a 2-rank run
(docs/performance.md, "Cost model"; issue 17 item 7).

In one invocation, on this machine:
  1. the case on 1 rank at four resolutions, the smallest almost all per-step overhead (bench/balance.py's cases and overrides): per coupled
     step the fluid's time (LIGGGHTS without the contact fix), the contact fix's and the rest
     (exchange with fsi-server, the multibody step, reductions, output);
  2. `mpirun -np 2 bench_mpi_pingpong`: one message's latency and bandwidth between two ranks;
  3. the contention of a host whose cores are all busy: two independent 1-rank runs at once (the
     resolution nearest half the finest) against the same run alone just before, `--repeat` pairs;
     their median ratio f (shared caches, memory bus, the servers and the OS on the same cores)
     scales every rank's compute when P >= 2;
  4. the case on 2 ranks at the finest resolution, which the model has not seen.

The model, per coupled step on P ranks of a grid px x py (x pz), the fluid's bounding box cut
evenly in particle counts (the client's balance):
  T(P) = l0 + f (a N / P + c(N) / P + r1 N / P) + r0 + t_halo(P) + t_collectives(P)
  (f = 1 on 1 rank, the measured contention on more)
  - l0 + a N: the fluid's time on 1 rank, a straight line through the 1-rank runs (relative
    least squares);
  - c(N): the contact fix on 1 rank (interpolated in N), shared evenly by the ranks;
  - r0 + r1 N: the rest of the 1-rank step, a straight line: r0 is serial (the exchange with the
    server, its multibody step, output), r1 N shrinks with P (the client's per-step scan of the
    fluid's health and its probes go over the rank's own particles);
  - t_halo = m (lambda + G b / B): every step LIGGGHTS sends its ghosts k times (m = k x 2
    messages per split axis, each lambda; G ghosts of b bytes, bandwidth B). G from the geometry:
    the particles within the ghost cut-off r_g of a rank's sub-domain, at the fluid's number
    density; r_g is LIGGGHTS' (pair cut-off + skin, from the client's log);
  - t_collectives = n_c ceil(log2 P) lambda: the reductions and broadcasts of one exchange and of
    LIGGGHTS' `run 1`.
The 1- and 2-rank runs pin their ranks (fsi-run --bind-to core: a machine given to one run), the
two runs of the contention measurement do not (pinned, both would run on core 0).
Assumptions (named in the output): k = 3 forward communications per step (positions and
velocities, density and pressure, fsi/ghost_sync), b = 80 bytes per ghost, n_c = 8; with
`newton off` (every example) a ghost's pairs are computed by its owner, so a ghost costs no pair
work; every rank runs on a core as fast as this machine's, every host as loaded as this one with
both its cores busy (f); the ranks are balanced.

Not a pass/fail test; the machine should be otherwise idle.

  bench/cost_model.py [--case dam_break|box_3d] [--resolutions 20,80,113,158] [--steps 300]
                      [--equilibration-steps 100] [--repeat 2] [--build build] [--json FILE]
"""
import argparse
import itertools
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import balance  # noqa: E402  (the cases and the coupled run)

# Assumptions of the model (docstring).
FORWARD_COMMS_PER_STEP = 3
BYTES_PER_GHOST = 80
COLLECTIVES_PER_STEP = 8
# Networks between hosts, assumed (not measured here): one message's latency [s] and bandwidth [B/s].
NETWORKS = {"InfiniBand HDR (assumed 1.5 us, 12 GB/s)": (1.5e-6, 12e9),
            "10 GbE (assumed 30 us, 1.1 GB/s)": (30e-6, 1.1e9)}
DEFAULT_RESOLUTIONS = {"dam_break": "20,80,113,158", "box_3d": "12,36,40,56"}


def fluid_extent(case, resolution, fill_height):
    """The fluid's bounding box at the start [m] (the case's lattice)."""
    if case == "dam_break":
        a = 0.028575  # martin_moyce_model.inc: column a wide, 2a high
        return [a, 2 * a, 0.0]
    spacing = 0.012 / resolution
    side = 0.012 - 2 * 1.2 * spacing  # one smoothing length off each side wall
    return [side, side, fill_height if fill_height is not None else 0.008]


def dimension_of(extent):
    return 3 if extent[2] > 0 else 2


def ghosts_of(extent, grid, particles, cutoff):
    """Ghosts of the sub-domain with the most cuts: at the fluid's number density, the band of
    width cutoff beyond each cut (one cut for 2 parts along an axis, two for an inner part)."""
    dim = dimension_of(extent)
    volume = math.prod(extent[:dim])
    density = particles / volume
    inner = 1.0
    widened = 1.0
    for k in range(dim):
        width = extent[k] / grid[k]
        cuts = 0 if grid[k] == 1 else (1 if grid[k] == 2 else 2)
        inner *= width
        widened *= width + cuts * cutoff
    return density * (widened - inner)


def best_grid(ranks, extent):
    """The grid with the shortest cuts through the fluid's box (the client's choice)."""
    dim = dimension_of(extent)
    best = None
    for px in range(1, ranks + 1):
        if ranks % px:
            continue
        rest = ranks // px
        for py in range(1, rest + 1):
            if rest % py:
                continue
            pz = rest // py
            if dim == 2 and pz != 1:
                continue
            if dim == 2:
                area = (px - 1) * extent[1] + (py - 1) * extent[0]
            else:
                area = ((px - 1) * extent[1] * extent[2] + (py - 1) * extent[0] * extent[2]
                        + (pz - 1) * extent[0] * extent[1])
            if best is None or area < best[0] - 1e-15:
                best = (area, (px, py, pz))
    return best[1]


def fit_line(xs, ys):
    """y = intercept + slope x by least squares in relative terms (weights 1/y^2), so that the
    smallest run, almost all per-step overhead, fixes the intercept; an intercept below 0
    (run-to-run noise: no step costs less than nothing) is replaced by the line through the origin."""
    w = [1.0 / max(y, 1e-12) ** 2 for y in ys]
    sw = sum(w)
    mx = sum(wi * x for wi, x in zip(w, xs)) / sw
    my = sum(wi * y for wi, y in zip(w, ys)) / sw
    sxx = sum(wi * (x - mx) ** 2 for wi, x in zip(w, xs))
    slope = sum(wi * (x - mx) * (y - my) for wi, x, y in zip(w, xs, ys)) / sxx
    if my - slope * mx < 0.0:
        return 0.0, sum(wi * x * y for wi, x, y in zip(w, xs, ys)) / sum(wi * x * x for wi, x in zip(w, xs))
    return my - slope * mx, slope


def interpolate(xs, ys, x):
    """Linear in log-log between the measured points (the contact fix's cost follows the
    particles near the walls, N^((D-1)/D) for a fixed geometry), extrapolated from the ends."""
    points = sorted(zip(xs, ys))
    lx = [math.log(p[0]) for p in points]
    ly = [math.log(max(p[1], 1e-12)) for p in points]
    i = 0 if math.log(x) <= lx[1] else len(points) - 2
    for j in range(len(points) - 1):
        if lx[j] <= math.log(x) <= lx[j + 1]:
            i = j
    t = (math.log(x) - lx[i]) / (lx[i + 1] - lx[i])
    return math.exp(ly[i] + t * (ly[i + 1] - ly[i]))


class Model:
    def __init__(self, runs, latency, bandwidth, cutoff, extent_of, contention=1.0):
        sizes = [r["particles"] for r in runs]
        self.l0, self.a = fit_line(sizes, [r["fluid"] for r in runs])
        self.contact_sizes = sizes
        self.contact = [r["contact"] for r in runs]
        self.r0, self.r1 = fit_line(sizes, [r["rest"] for r in runs])
        self.latency, self.bandwidth = latency, bandwidth
        self.cutoff = cutoff
        self.extent_of = extent_of
        self.contention = contention

    def terms(self, particles, ranks, grid=None, latency=None, bandwidth=None):
        latency = self.latency if latency is None else latency
        bandwidth = self.bandwidth if bandwidth is None else bandwidth
        extent = self.extent_of(particles)
        grid = grid or best_grid(ranks, extent)
        split_axes = sum(1 for p in grid if p > 1)
        ghosts = ghosts_of(extent, grid, particles, self.cutoff) if ranks > 1 else 0.0
        halo = 0.0
        if ranks > 1:
            messages = FORWARD_COMMS_PER_STEP * 2 * split_axes
            halo = messages * latency + FORWARD_COMMS_PER_STEP * ghosts * BYTES_PER_GHOST / bandwidth
        collectives = COLLECTIVES_PER_STEP * math.ceil(math.log2(ranks)) * latency if ranks > 1 else 0.0
        f = self.contention if ranks > 1 else 1.0
        return {"grid": grid, "ghosts": ghosts,
                "fluid": self.l0 + f * self.a * particles / ranks,
                "contact": f * interpolate(self.contact_sizes, self.contact, particles) / ranks,
                "halo": halo, "collectives": collectives,
                "rest": self.r0 + f * self.r1 * particles / ranks}

    def step(self, particles, ranks, **kwargs):
        t = self.terms(particles, ranks, **kwargs)
        return t["fluid"] + t["contact"] + t["halo"] + t["collectives"] + t["rest"]


def pingpong(bin_dir):
    command = ["mpirun", "-np", "2", os.path.join(bin_dir, "bench_mpi_pingpong"), "--json"]
    out = subprocess.run(command, env=balance.ENV, check=True, capture_output=True, text=True).stdout
    result = json.loads(out.strip().splitlines()[-1])
    return result["latency_s"], result["bandwidth_bytes_per_s"]


def per_step(run, decomposition):
    t = run["timings_seconds"]
    steps = run["steps"]
    ghost_line = next((line for line in decomposition if line.startswith("ghosts:")), "")
    cutoff = re.search(r"ghost cut-off ([0-9.eE+-]+) m", ghost_line)
    ghosts = [int(v) for v in re.findall(r"\d+", ghost_line.split("per rank")[0])] if ghost_line else []
    grid = re.search(r"decomposition: (\d+) x (\d+) x (\d+)", " ".join(decomposition))
    return {"particles": run["fluid"]["particle_count"], "steps": steps,
            "step": t["coupled_phase"] / steps,
            # run.json's "liggghts" is LIGGGHTS' step without the contact fix inside it.
            "fluid": t["liggghts"] / steps,
            "contact": t["contact_fix"] / steps,
            "rest": (t["coupled_phase"] - t["liggghts"] - t["contact_fix"]) / steps,
            "cutoff": float(cutoff.group(1)) if cutoff else None,
            "ghosts": ghosts,
            "grid": tuple(int(g) for g in grid.groups()) if grid else None}


def concurrent_step(bin_dir, folder, case, overrides):
    """The faster of two independent 1-rank runs started together (coupled phase per step)."""
    jobs = []
    for k in range(2):
        run_dir = os.path.join(folder, f"concurrent_{k}")
        # Unpinned: pinned, both runs' rank 0 would share core 0 (Open MPI binds rank i to core i).
        command = balance.fsi_run_command(bin_dir, balance.SCENES[case], run_dir, 1, overrides, bind="none")
        jobs.append((run_dir, subprocess.Popen(command, env=balance.ENV, stdout=subprocess.DEVNULL,
                                               stderr=subprocess.DEVNULL)))
    steps = []
    for run_dir, job in jobs:
        if job.wait() != 0:
            raise RuntimeError(f"the concurrent run in {run_dir} failed ({job.returncode})")
        with open(os.path.join(run_dir, "run.json")) as handle:
            run = json.load(handle)
        steps.append(run["timings_seconds"]["coupled_phase"] / run["steps"])
    return min(steps)


def fastest(bin_dir, folder, case, name, ranks, overrides, repeat):
    """The run with the shortest coupled phase of `repeat` runs."""
    best = None
    for k in range(max(1, repeat)):
        run = per_step(*balance.coupled(bin_dir, folder, balance.SCENES[case], f"{name}_{k}", ranks,
                                        overrides, []))
        if best is None or run["step"] < best["step"]:
            best = run
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--case", choices=sorted(balance.SCENES), default="dam_break")
    parser.add_argument("--resolutions", default=None,
                        help="three or more 1-rank resolutions, the last also run on 2 ranks "
                             "(default: dam_break 20,80,113,158; box_3d 12,36,40,56: at 45 and 48 the unsettled lattice of a 100-step settling blows up at release)")
    parser.add_argument("--steps", type=int, default=300, help="coupled steps measured per run")
    parser.add_argument("--equilibration-steps", type=int, default=100)
    parser.add_argument("--fill-height", type=float, default=None, help="box_3d: the water's height [m]")
    parser.add_argument("--build", default=os.path.join(balance.ROOT, "build"))
    parser.add_argument("--repeat", type=int, default=2,
                        help="runs per point; the fastest counts (default 2)")
    parser.add_argument("--json", default=None, help="also write the measurements and predictions here")
    args = parser.parse_args()
    resolutions = [int(r) for r in (args.resolutions or DEFAULT_RESOLUTIONS[args.case]).split(",")]
    if len(resolutions) < 3 or sorted(resolutions) != resolutions:
        parser.error("--resolutions: give three or more, ascending")
    bin_dir = os.path.join(args.build, "bin")

    latency, bandwidth = pingpong(bin_dir)
    runs = []
    with tempfile.TemporaryDirectory(prefix="fsi_cost_model_") as folder:
        for resolution in resolutions:
            overrides, _, _ = balance.case_overrides(args.case, resolution, args.steps,
                                                    args.equilibration_steps, args.fill_height)
            runs.append(fastest(bin_dir, folder, args.case, f"np1_{resolution}", 1, overrides, args.repeat))
        # Contention: the resolution whose particle count is nearest half the finest's.
        half = min(range(len(runs)), key=lambda i: abs(runs[i]["particles"] - runs[-1]["particles"] / 2))
        overrides, _, _ = balance.case_overrides(args.case, resolutions[half], args.steps,
                                                 args.equilibration_steps, args.fill_height)
        # Each pair (the run alone, pinned, then two at once) back to back, so that the VM's drift
        # between minutes (up to 25 %) falls out of each ratio; f is their median.
        pairs = []
        for k in range(max(1, args.repeat)):
            alone = per_step(*balance.coupled(bin_dir, folder, balance.SCENES[args.case],
                                              f"alone_{k}", 1, overrides, []))["step"]
            pairs.append((alone, concurrent_step(bin_dir, folder, args.case, overrides)))
        contention = max(1.0, statistics.median(together / alone for alone, together in pairs))
        overrides, _, described = balance.case_overrides(args.case, resolutions[-1], args.steps,
                                                         args.equilibration_steps, args.fill_height)
        measured2 = fastest(bin_dir, folder, args.case, "np2", 2, overrides, args.repeat)

    cutoff = runs[-1]["cutoff"]
    largest = runs[-1]["particles"]
    base_extent = fluid_extent(args.case, resolutions[-1], args.fill_height)
    dim = dimension_of(base_extent)

    def extent_of(particles):
        # A larger case of the same shape: every length grows with (N / N_measured)^(1/D) at the
        # same spacing.
        scale = (particles / largest) ** (1.0 / dim)
        return [e * scale for e in base_extent]

    model = Model(runs, latency, bandwidth, cutoff, extent_of, contention)
    print(f"{args.case}: cost model from {len(runs)} 1-rank runs ({args.steps} coupled steps each), "
          f"ghost cut-off {cutoff:.4g} m (LIGGGHTS), MPI ping-pong on this machine: latency "
          f"{1e6 * latency:.2f} us, bandwidth {bandwidth / 1e9:.2f} GB/s")
    print(f"  1-rank runs: " + "; ".join(
        f"N = {r['particles']}: {1e3 * r['step']:.3f} ms/step (fluid {1e3 * r['fluid']:.3f}, contact "
        f"{1e3 * r['contact']:.3f}, rest {1e3 * r['rest']:.3f})" for r in runs))
    print(f"  each the fastest of {args.repeat} run(s)")
    print(f"  fitted: fluid = {1e3 * model.l0:.4f} ms + {1e9 * model.a:.2f} ns x N per step; rest = "
          f"{1e3 * model.r0:.4f} ms (serial) + {1e9 * model.r1:.2f} ns x N per step")
    print(f"  contention: N = {runs[half]['particles']}, alone then two at once, back to back: "
          + "; ".join(f"{1e3 * alone:.3f} -> {1e3 * together:.3f} ms/step" for alone, together in pairs)
          + f": f = {contention:.3f} (the median ratio, at least 1)")
    print(f"  assumed: {FORWARD_COMMS_PER_STEP} forward communications per step of {BYTES_PER_GHOST} B "
          f"per ghost, {COLLECTIVES_PER_STEP} collectives per step, no pair work for ghosts (newton "
          f"off), balanced ranks, every core as fast as this machine's")

    grid2 = measured2["grid"] or best_grid(2, base_extent)
    terms2 = model.terms(largest, 2, grid=grid2)
    predicted2 = model.step(largest, 2, grid=grid2)
    error = predicted2 / measured2["step"] - 1.0
    print(f"\n2 ranks, {described}, N = {largest}, grid {grid2[0]} x {grid2[1]} x {grid2[2]} "
          f"(not used in the fit):")
    print(f"  predicted {1e3 * predicted2:.3f} ms/step (fluid {1e3 * terms2['fluid']:.3f}, contact "
          f"{1e3 * terms2['contact']:.3f}, halo {1e3 * terms2['halo']:.4f} for {terms2['ghosts']:.0f} "
          f"ghosts, collectives {1e3 * terms2['collectives']:.4f}, rest {1e3 * terms2['rest']:.3f})")
    ghosts_measured = " / ".join(str(g) for g in measured2["ghosts"]) or "?"
    print(f"  measured  {1e3 * measured2['step']:.3f} ms/step (fluid {1e3 * measured2['fluid']:.3f}, contact "
          f"{1e3 * measured2['contact']:.3f}, rest {1e3 * measured2['rest']:.3f}, as rank 0 timed them; "
          f"ghosts per rank at the end: {ghosts_measured}); prediction {100 * error:+.1f} %")

    print("\nPredicted ms per coupled step (speed-up over 1 rank) on P ranks:")
    sizes = [largest, 20 * largest]
    header = "| network | " + " | ".join(f"N = {n:.3g}, P = {p}" for n, p in itertools.product(sizes, (8, 64, 512)))
    print(header + " |")
    print("|" + "---|" * (1 + 3 * len(sizes)))
    networks = {f"one host's shared memory (measured {1e6 * latency:.2f} us, {bandwidth / 1e9:.1f} GB/s)":
                (latency, bandwidth)}
    networks.update(NETWORKS)
    predictions = {}
    for name, (lat, bw) in networks.items():
        cells = []
        for n, p in itertools.product(sizes, (8, 64, 512)):
            t1 = model.step(n, 1)
            tp = model.step(n, p, latency=lat, bandwidth=bw)
            if model.terms(n, p)["ghosts"] > n / p:
                # A sub-domain narrower than the ghost cut-off: a rank holds more copies than
                # particles, which the model (ghosts cost only their messages) does not describe.
                cells.append(f"beyond the model ({n / p:.0f} per rank)")
                continue
            predictions[f"{name}|{n}|{p}"] = tp
            cells.append(f"{1e3 * tp:.3f} ({t1 / tp:.1f}x)")
        print(f"| {name} | " + " | ".join(cells) + " |")
    print(f"  1 rank: N = {largest}: {1e3 * model.step(largest, 1):.3f} ms/step; N = {20 * largest}: "
          f"{1e3 * model.step(20 * largest, 1):.3f} ms/step (the fit extrapolated)")
    if args.json:
        with open(args.json, "w") as handle:
            json.dump({"case": args.case, "runs": runs, "np2": measured2, "latency_s": latency,
                       "bandwidth": bandwidth, "predicted_np2": predicted2, "error_np2": error,
                       "fit": {"l0": model.l0, "a": model.a, "r0": model.r0, "r1": model.r1, "contention": contention},
                       "predictions": predictions}, handle, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
