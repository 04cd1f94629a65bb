#!/usr/bin/python3
"""Flexible fibres in a flow (examples/fibres/fibres_coarse.scene; thesis Figs 7.6-7.10, issue 17
item 4): a water column released at t = 0 surges along a closed channel through 3 x 3 fibres,
each an AncfCable3D of two elements with a tube surface, clamped upright on the floor. fsi-run on
2 ranks at the coarse resolution, cut to END seconds after 0.025 s of settling (the first row's
deflection peaks at about 0.08 s).

Checked: the run completes with no lost particle and action = reaction at every exchange; the
surge reaches the probe in front of the array and moves there; the first row's tips are pushed
downstream (+x) by more than 1 mm, and the fluid's force on the first fibre points downstream;
analyze.py draws the run. (The same run with fibres 100 times stiffer moved their tips 0.017 times
as far: 0.054 against 3.215 mm; run_four.py runs all four cases, docs/validation.md; a second
coupled run here would cost the suite another two minutes.)"""
import os
import subprocess
import sys

from fsi_test import check, cleanup, example, fsi_run_checked, work_dir

sys.path.insert(0, os.path.dirname(example("fibres", "analyze.py")))
sys.path.insert(0, os.path.dirname(os.path.dirname(example("fibres", "analyze.py"))))
from fsi_results import read_run  # noqa: E402

END = 0.08
output = work_dir("fibres")
scene = example("fibres", "fibres_coarse.scene")


def run(name, overrides):
    run_dir = os.path.join(output, name)
    record = fsi_run_checked(scene, run_dir, 2,
                             [f"Resolution.end_time={END}", "Resolution.equilibration_steps=1000"] + list(overrides),
                             label=f"{name}: ")
    checks = record["checks"]
    check(checks["max_action_reaction_relative"] <= 1e-12,
          f"{name}: action = reaction at every exchange ({checks['max_action_reaction_relative']:.3e})")
    return read_run(run_dir)[1], run_dir


def deflections(sensors, fibre):
    x = sensors[f"tip_{fibre}_x"]
    return [value - x[0] for value in x]


soft, soft_dir = run("soft", [])
time = soft["time"]
wet = [t for t, w in zip(time, soft["front_wet"]) if w > 0]
check(bool(wet), "the surge reaches the probe in front of the fibres")
speed = max((vx * vx + vy * vy + vz * vz) ** 0.5
            for vx, vy, vz in zip(soft["front_vx"], soft["front_vy"], soft["front_vz"]))
print(f"measured: the surge reaches the front probe at {wet[0]:.4f} s, peak speed there {speed:.3f} m/s")
check(speed > 0.2, f"the water in front of the fibres moves ({speed:.3f} m/s > 0.2)")
for fibre in ("12", "13"):
    largest = max(deflections(soft, fibre))
    print(f"measured: fibre_{fibre} (first row) tip, largest dx {1e3 * largest:+.3f} mm")
    check(largest > 1e-3, f"fibre_{fibre}'s tip is pushed downstream ({1e3 * largest:.3f} mm > 1 mm)")
force = soft["fibre_13_fluid_x"]
check(max(force) > 0 and max(force) > -min(force),
      f"the fluid pushes the first fibre downstream (largest +x {max(force):.3e} N, -x {min(force):.3e} N)")

result = subprocess.run([sys.executable, example("fibres", "analyze.py"), soft_dir,
                         "--figure-prefix", os.path.join(output, "fibres")],
                        capture_output=True, text=True, timeout=120)
print(result.stdout[-3000:], result.stderr[-2000:])
check(result.returncode == 0, "analyze.py reads the run")
for figure in ("fibres_speed.png", "fibres_tips.png"):
    path = os.path.join(output, figure)
    check(os.path.isfile(path) and os.path.getsize(path) > 10000, f"analyze.py drew {figure}")
cleanup(output)
print("PASS")
