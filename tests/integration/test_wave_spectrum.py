#!/usr/bin/python3
"""run.json records each wavemaker's waves (format_version 9, "wavemakers"), and
examples/wave_flume/spectrum.py analyses an irregular sea from the run alone.

The flap flume's wavemaker as a JONSWAP sea (H_s = 0.05 m, 32 components), --mbd-only for 0.01 s:
its record holds the sea asked for and the 32 components, at whole multiples of one spacing that
sets the repeat period, their heights summing to 4 sqrt(m0) = H_s. Then made-up gauge records
built from those components (one gauge at 80 % of every height, one at 100 %) are written as the
run's sensors.csv, and spectrum.py must find H_m0 -20 % and 0 %, pass with --max-hm0-error 0.25
and fail with 0.1; a run without an irregular wavemaker is refused with a message."""
import math
import os
import subprocess
import sys

from fsi_test import ENV, binary, check, cleanup, example, fail, work_dir
from run_manifest import read_run_manifest

output = work_dir("wave_spectrum")
run_dir = os.path.join(output, "sea")
command = [binary("fsi-server"), example("wave_flume", "wave_flume_flap.scene"), "--mbd-only",
           "--output", run_dir, "--set", 'FlapWavemaker.spectrum="jonswap"', "--set",
           "FlapWavemaker.components=32", "--set", "FlapWavemaker.height=0.05", "--set",
           "Resolution.end_time=0.01"]
result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=120)
if result.returncode != 0:
    fail(f"{' '.join(command)} exited {result.returncode}:\n{result.stderr[-3000:]}")
run = read_run_manifest(run_dir)
check(len(run["wavemakers"]) == 1, f"one wavemaker recorded ({len(run['wavemakers'])})")
sea = run["wavemakers"][0]
check((sea["name"], sea["body"], sea["kind"], sea["spectrum"]) == ("stroke", "paddle", "flap", "jonswap"),
      f"its name, paddle, kind and spectrum: {sea['name']}, {sea['body']}, {sea['kind']}, {sea['spectrum']}")
check((sea["height"], sea["period"], sea["peak_enhancement"]) == (0.05, 1.4, 3.3),
      f"the sea asked for: H_s {sea['height']} m, T_p {sea['period']} s, gamma {sea['peak_enhancement']}")
components = sea["components"]
omegas, heights = components["omega"], components["height"]
check(len(omegas) == 32 and all(len(components[key]) == 32 for key in ("height", "half_stroke", "phase")),
      "32 components, each with omega, height, half stroke and phase")
spacing = 2 * math.pi / sea["repeat_period"]
multiples = [w / spacing for w in omegas]
check(all(abs(m - round(m)) < 1e-9 for m in multiples)
      and all(round(b) - round(a) == 1 for a, b in zip(multiples, multiples[1:])),
      f"consecutive whole multiples of 2 pi / {sea['repeat_period']} s "
      f"({round(multiples[0])}..{round(multiples[-1])})")
hm0 = 4 * math.sqrt(sum(h * h for h in heights) / 8)
check(abs(hm0 - 0.05) < 1e-12, f"4 sqrt(m0) of the components is H_s ({hm0:.15f} m)")
check(all(s > 0 for s in components["half_stroke"]), "every component has a stroke")

# Made-up gauges from the recorded components, one repeat period from t = 1 s, and spectrum.py.
start, step = 1.0, 0.02
count = int((start + sea["repeat_period"]) / step) + 2
with open(os.path.join(run_dir, "sensors.csv"), "w") as handle:
    handle.write("# made up by test_wave_spectrum.py\ntime,g10_elevation,g14_elevation\n")
    for n in range(count):
        t = n * step
        full = sum(0.5 * h * math.cos(w * t + p) for w, h, p in zip(omegas, heights, components["phase"]))
        handle.write(f"{t:.6f},{0.8 * full:.9e},{full:.9e}\n")
spectrum = example("wave_flume", "spectrum.py")


def analyse(*extra):
    return subprocess.run([sys.executable, spectrum, run_dir, "--start", str(start), *extra],
                          env=ENV, capture_output=True, text=True, timeout=120)


passed = analyse("--max-hm0-error", "0.25")
print(passed.stdout, passed.stderr)
check(passed.returncode == 0, f"spectrum.py reads the sea from run.json and passes at 25 % (exit {passed.returncode})")
check("x = 1.0 m: H_m0 = 0.0400 m (-20.0 % from H_s)" in passed.stdout
      and "x = 1.4 m: H_m0 = 0.0500 m (+0.0 % from H_s)" in passed.stdout,
      "it finds the made-up gauges' H_m0: -20 % and 0 %")
failed = analyse("--max-hm0-error", "0.1")
check(failed.returncode == 1 and "FAIL H_m0 at g10: -20.0 %" in failed.stdout,
      f"and fails at 10 % (exit {failed.returncode})")

# A run without an irregular wavemaker: refused, saying so.
regular_dir = os.path.join(output, "regular")
subprocess.run([binary("fsi-server"), example("wave_flume", "wave_flume_flap.scene"), "--mbd-only",
                "--output", regular_dir, "--set", "Resolution.end_time=0.01"],
               env=ENV, capture_output=True, text=True, timeout=120, check=True)
refused = subprocess.run([sys.executable, spectrum, regular_dir], env=ENV, capture_output=True,
                         text=True, timeout=120)
check(refused.returncode != 0 and "0 irregular wavemakers match (the run's wavemakers: stroke (regular))"
      in refused.stderr, f"a regular wave is refused: {refused.stderr.strip()}")
cleanup(output)
