#!/usr/bin/python3
"""A constraint released at a chosen time through the scene (issue 19, `release_time`): a block
held by three coordinate constraints, y released at 0.25 s, inside a step of 0.02 s. With every
integrator of `--mbd-only` (fixed Radau IIA, IDA, adaptive Radau IIA) the block stays at y0 with
its constraint-force sensor at m g until the release, then falls as y0 - g (t - 0.25)^2 / 2 with
the sensor at 0."""
import os
import subprocess

from fsi_test import ENV, binary, check, cleanup, fail, load_sensors, manifest, work_dir

SCENE = """scene_language = 1
SolverOptions { end_time = 0.6; Timeint { step_size = 0.02 } }
Gravity { acceleration = [0, -9.81] }
RigidBody2D { name = "block"; mass = 2; inertia = 0.1; position = [0, 1] }
CoordinateConstraint { body = "block"; coordinate = "x" }
CoordinateConstraint { body = "block"; coordinate = "y"; release_time = 0.25 }
CoordinateConstraint { body = "block"; coordinate = "angle" }
Sensor { name = "y"; type = "position"; body = "block"; component = "y" }
Sensor { name = "held_force_y"; type = "constraint_force"; body = "block"; component = "y" }
"""
RELEASE, WEIGHT, TOLERANCE = 0.25, 2 * 9.81, {"fixed": 1e-12, "ida": 1e-9, "adaptive": 1e-12}

output = work_dir("release_time")
scene = os.path.join(output, "drop.scene")
with open(scene, "w") as handle:
    handle.write(SCENE)

for method, tolerance in TOLERANCE.items():
    run_dir = os.path.join(output, method)
    result = subprocess.run([binary("fsi-server"), scene, "--mbd-only", "--output", run_dir, "--set",
                             f'SolverOptions.Timeint.method="{method}"'],
                            env=ENV, capture_output=True, text=True, timeout=120)
    if result.returncode != 0:
        fail(f"{method}: fsi-server --mbd-only exited {result.returncode}:\n{result.stderr[-3000:]}")
    check(manifest(run_dir)["status"] == "completed", f"{method}: the run completes")
    sensors = load_sensors(run_dir)
    held = [i for i, t in enumerate(sensors["time"]) if t < RELEASE]
    free = [i for i, t in enumerate(sensors["time"]) if t > RELEASE]
    height_before = max(abs(sensors["y"][i] - 1.0) for i in held)
    force_before = max(abs(sensors["held_force_y"][i] - WEIGHT) for i in held)
    fall = max(abs(sensors["y"][i] - (1.0 - 0.5 * 9.81 * (sensors["time"][i] - RELEASE) ** 2)) for i in free)
    force_after = max(abs(sensors["held_force_y"][i]) for i in free)
    check(height_before < 1e-12 and force_before < 1e-9,
          f"{method}: held at y0 (to {height_before:.1e} m) by m g (to {force_before:.1e} N/m) before the release")
    check(fall < tolerance, f"{method}: falls with g from 0.25 s on (to {fall:.1e} m)")
    check(force_after == 0.0, f"{method}: its constraint force reads {force_after} after the release")
cleanup(output)
print("release_time: passed")
