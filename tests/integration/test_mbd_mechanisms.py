#!/usr/bin/python3
"""`fsi-server --mbd-only` on examples/mbd_mechanisms: the prismatic joint, torsion spring and
one-sided spring actor against their closed forms (the example's analyze.py), the new sensor
columns finite; Turek & Hron's CSM3 flag and the elastica (analyze_csm3.py, analyze_elastica.py);
and bad mechanisms named: a spring law that turns NaN stops the run with exit 1
naming the spring, at its step, with no NaN in sensors.csv; a redundant joint is refused before
step 0 naming the joint."""
import math
import os
import shutil
import subprocess

from fsi_test import ENV, binary, check, cleanup, example, fail, load_sensors, manifest, work_dir

output = work_dir("mbd_mechanisms")
run_dir = os.path.join(output, "run")
scene = example("mbd_mechanisms", "mbd_mechanisms.scene")
result = subprocess.run([binary("fsi-server"), scene, "--mbd-only", "--output", run_dir],
                        env=ENV, capture_output=True, text=True, timeout=120)
if result.returncode != 0:
    fail(f"fsi-server --mbd-only exited {result.returncode}:\n{result.stderr[-3000:]}")
check(manifest(run_dir)["status"] == "completed", "the mechanisms run completes")
analysis = subprocess.run(["/usr/bin/python3", example("mbd_mechanisms", "analyze.py"), run_dir],
                          capture_output=True, text=True, timeout=60)
print(analysis.stdout, end="")
check(analysis.returncode == 0, "every expected number of examples/mbd_mechanisms/README.md holds")

# The two structural benchmarks of the same folder, each with its own analysis (about 1 s each):
# Turek & Hron's CSM3 flag and the elastica at lam = 1 and 10 (a static shape the damped beam
# settles to); a damper's work sensor against the pendulum's energy change; an actuator (a
# spring law in time) against the closed form; and a door closer (a 3D rotational spring-damper)
# against the damped oscillator's closed form.
for name, scene_file, script, settings in (
        ("csm3", "turek_hron_csm3.scene", "analyze_csm3.py", []),
        ("elastica1", "elastica.scene", "analyze_elastica.py", ["--set", "Geometry.lam=1"]),
        ("elastica10", "elastica.scene", "analyze_elastica.py", []),
        ("pendulum", "damped_pendulum.scene", "analyze_pendulum.py", []),
        ("actuator", "actuator.scene", "analyze_actuator.py", []),
        ("door", "door_closer_3d.scene", "analyze_door.py", [])):
    bench_dir = os.path.join(output, name)
    result = subprocess.run([binary("fsi-server"), example("mbd_mechanisms", scene_file), "--mbd-only",
                             "--output", bench_dir] + settings, env=ENV, capture_output=True, text=True, timeout=120)
    if result.returncode != 0:
        fail(f"fsi-server --mbd-only {scene_file} exited {result.returncode}:\n{result.stderr[-3000:]}")
    analysis = subprocess.run(["/usr/bin/python3", example("mbd_mechanisms", script), bench_dir],
                              capture_output=True, text=True, timeout=60)
    print(analysis.stdout, end="")
    check(analysis.returncode == 0, f"{name}: {script} finds the benchmark's numbers")

# The same scene with bad mechanisms, in a copy of the example folder.
bad_dir = os.path.join(output, "bad")
os.makedirs(bad_dir)
for name in ("mbd_mechanisms.scene", "mbd_mechanisms.in"):
    shutil.copy(example("mbd_mechanisms", name), bad_dir)
with open(scene) as handle:
    text = handle.read()

# Hangs the valve from a point above; the law turns NaN once the falling valve has stretched it by
# 2 cm (sqrt of a negative number, after about 0.064 s).
with open(os.path.join(bad_dir, "nan.scene"), "w") as handle:
    handle.write(text + 'NonlinearSpringDamper { name = "brittle"; body_a = "valve"; point_b = [4, 1];'
                        ' tension = "sqrt(0.02 - elongation)" }\n')
nan_run = os.path.join(bad_dir, "nan_run")
result = subprocess.run([binary("fsi-server"), os.path.join(bad_dir, "nan.scene"), "--mbd-only",
                         "--output", nan_run], env=ENV, capture_output=True, text=True, timeout=60)
check(result.returncode == 1, f"a NaN spring law: exit 1 (got {result.returncode})")
check("not finite: nonlinear spring-damper 'brittle'" in result.stderr,
      "the message names the spring that turned NaN")
bad = manifest(nan_run)
check(bad["status"] == "failed" and "brittle" in bad.get("reason", ""), "run.json says failed, naming it")
rows = load_sensors(nan_run)
check(len(rows["time"]) > 0 and all(math.isfinite(v) for column in rows.values() for v in column),
      f"sensors.csv ends at t = {rows['time'][-1]} s, the last good row, with no NaN or inf")

# The door closer wound past the half turn it measures: the door let go 150 degrees open and pushed
# shut at 3 rad/s against an undamped closer swings through shut to beyond -170 degrees (its
# amplitude 187): the run stops naming the closer and the twist.
wound_run = os.path.join(bad_dir, "wound_run")
result = subprocess.run([binary("fsi-server"), example("mbd_mechanisms", "door_closer_3d.scene"), "--mbd-only",
                         "--output", wound_run, "--set", "Geometry.c=0", "--set", "Geometry.open=pi*150/180",
                         "--set", "Geometry.spin=-3"],
                        env=ENV, capture_output=True, text=True, timeout=60)
check(result.returncode == 1, f"a closer wound past +-170 degrees: exit 1 (got {result.returncode})")
check("rotational spring-damper 'closer': twisted past" in result.stderr and "+-170 degrees from its rest angle" in result.stderr,
      "the message names the closer and its twist:\n" + result.stderr[-600:])
check(manifest(wound_run)["status"] == "failed", "run.json says failed")

with open(os.path.join(bad_dir, "redundant.scene"), "w") as handle:
    handle.write(text + 'Clamp { name = "glue"; body = "wheel" }\n')
result = subprocess.run([binary("fsi-server"), os.path.join(bad_dir, "redundant.scene"), "--mbd-only",
                         "--output", os.path.join(bad_dir, "redundant_run")],
                        env=ENV, capture_output=True, text=True, timeout=60)
check(result.returncode != 0, f"a redundant clamp is refused (exit {result.returncode})")
check("clamp 'glue' (x): redundant" in result.stderr, "the message names the redundant clamp row")
cleanup(output)
print("mbd mechanisms: 2 passed, 0 failed")
