#!/usr/bin/python3
"""Channel flows between our walls (issue 13, examples/channel_flows): Poiseuille and Couette flow
from rest, periodic along x (fix fsi/sph adds the walls' periodic images), at 40 particles across
(the `_medium` scenes), against the series solutions of Morris et al. (1997). This resolution's
own tolerances (docs/validation.md, "Channel flows"; at 80 across issue 13's 5 % and 3 % hold):
the centre velocity at t = 0.5 s within 3 % of the series, the profile at every Morris time within
10 % of the peak velocity, and the viscosity fitted over every row within 0.8-1.25 nu (the scene's
nu maps to LIGGGHTS' alpha = 16 nu/(c h), its walls' t = rho0 nu / r_v). Two runs of 10-30 s each
(480 particles, 8 800 steps, one rank)."""
import json
import os
import subprocess

from fsi_test import binary, check, example, work_dir, ENV

ANALYZE = example("channel_flows", "analyze.py")
work = work_dir("channel_flows")

for flow in ("poiseuille", "couette"):
    output = os.path.join(work, flow)
    command = [binary("fsi-run"), example("channel_flows", f"{flow}_medium.scene"), "--np", "1", "--output", output]
    result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=300)
    print(result.stderr[-2000:])
    check(result.returncode == 0, f"{flow}: fsi-run exits 0 (got {result.returncode})")
    analysis = subprocess.run(["/usr/bin/python3", ANALYZE, output, "--flow", flow, "--particles-across", "40",
                               "--profile-tolerance", "0.10", "--centre-tolerance", "0.03"],
                              env=ENV, capture_output=True, text=True, timeout=120)
    print(analysis.stdout)
    check(analysis.returncode == 0, f"{flow}: analyze.py passes the tolerances of 40 across (exit {analysis.returncode})")
    with open(os.path.join(output, "analysis.json")) as handle:
        figures = json.load(handle)
    times = [round(p["time"], 4) for p in figures["profiles"]]
    check(times == [0.0225, 0.045, 0.1125, 0.225, 0.5], f"{flow}: the profiles at the Morris times and the end: {times}")
    check(abs(figures["centre_error"]) <= 0.03, f"{flow}: centre {100 * figures['centre_error']:+.2f} % (within 3 %)")
    check(0.8 <= figures["nu_fit"] / 1e-6 <= 1.25, f"{flow}: fitted nu = {figures['nu_fit'] / 1e-6:.3f} nu (0.8-1.25)")
    with open(os.path.join(output, "run.json")) as handle:
        run = json.load(handle)
    check(run["status"] == "completed", f"{flow}: run completed")
    check(not any("viscosity_match" in w for w in run.get("warnings", [])),
          f"{flow}: the wall's t and the fluid's alpha agree (no viscosity_match warning)")
