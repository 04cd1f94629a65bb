#!/usr/bin/python3
"""A scene holds only what its mode uses (issue 18): an `--mbd-only` scene of two bodies, a
revolute joint and a spring runs with no surface mesh, no LIGGGHTS block (nor its two scripts)
and no Coupling block. The undamped pendulum with a spring-held bob keeps its energy (kinetic +
potential, gravity and spring) to the integrator's accuracy. `--check --mbd-only` names what the
mode needs; the same scene run coupled is refused, naming the three missing pieces."""
import math
import os
import subprocess

from fsi_test import SPRING_PENDULUM, ENV, binary, check, cleanup, example, fail, load_sensors, manifest, work_dir

SCENE = SPRING_PENDULUM + """SolverOptions { end_time = 0.5; Timeint { step_size = 1e-3 } }
Sensor { name = "bob_y"; type = "position"; body = "bob"; component = "y" }
Sensor { name = "tension"; type = "spring_force"; element = "spring" }
"""

output = work_dir("mbd_only_minimal")
scene = os.path.join(output, "pendulum.scene")
with open(scene, "w") as handle:
    handle.write(SCENE)

check_run = subprocess.run([binary("fsi-server"), scene, "--check", "--mbd-only"], env=ENV,
                           capture_output=True, text=True, timeout=60)
if check_run.returncode != 0:
    fail(f"--check --mbd-only exited {check_run.returncode}:\n{check_run.stderr[-3000:]}")
check("an --mbd-only run needs: SolverOptions\n" in check_run.stdout,
      "--check --mbd-only says the mode needs SolverOptions only")

# A scene with a fluid, checked for --mbd-only: the fluid is not built, and the fluid's rules of
# thumb are not judged against an empty fluid (no warnings from zero particle mass and spacing).
tank = subprocess.run([binary("fsi-server"), example("static_tank", "static_tank_coarse.scene"), "--check",
                       "--mbd-only"], env=ENV, capture_output=True, text=True, timeout=60)
check(tank.returncode == 0 and "0 warning(s)" in tank.stdout and "FluidRegion, LIGGGHTS" in tank.stdout,
      "--check --mbd-only of the static tank: fluid blocks named as not read, no physics warnings")

coupled = subprocess.run([binary("fsi-server"), scene, "--check"], env=ENV, capture_output=True,
                         text=True, timeout=60)
check(coupled.returncode == 2, f"the same scene checked for a coupled run is refused ({coupled.returncode})")
for missing in ("required block 'LIGGGHTS' is missing", "required block 'Coupling' is missing",
                "the scene has no surface mesh"):
    check(missing in coupled.stderr, f"the coupled check says: {missing}")

run_dir = os.path.join(output, "run")
result = subprocess.run([binary("fsi-server"), scene, "--mbd-only", "--output", run_dir], env=ENV,
                        capture_output=True, text=True, timeout=120)
if result.returncode != 0:
    fail(f"fsi-server --mbd-only exited {result.returncode}:\n{result.stderr[-3000:]}")
check(manifest(run_dir)["status"] == "completed", "the run without mesh, LIGGGHTS and Coupling completes")

sensors = load_sensors(run_dir)
check(all(math.isfinite(v) for column in sensors.values() for v in column), "no NaN or inf in sensors.csv")
check(min(sensors["bob_y"]) < -0.5, f"the bob falls (lowest y = {min(sensors['bob_y']):.3f} m)")
check(max(abs(t) for t in sensors["tension"]) > 1.0, "the spring carries load")
energy = [k + p for k, p in zip(sensors["kinetic"], sensors["potential"])]
drift = max(abs(e - energy[0]) for e in energy)
check(drift < 1e-8, f"energy kept to {drift:.1e} J/m (< 1e-8)")
cleanup(output)
print("mbd-only minimal scene: passed")
