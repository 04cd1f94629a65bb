#!/usr/bin/python3
"""The flexibly mounted rotor in a duct (examples/rotor/rotor_coarse.scene; thesis Figs 7.3-7.5,
issue 17 item 3): a five-blade rigid rotor (STL) driven at 40 rad/s by a RevoluteJoint3D with a
rate in a carrier that hangs on ten SpringDamper3D, in water with a free surface in a duct that
is periodic along x. fsi-run on 2 ranks at the coarse resolution to END seconds.

Checked: the run completes with no lost particle and action = reaction at every exchange; the rotor
pumps water towards +x through the duct's section at both flux probes (over the second half of
the run, where the flow has spun up) and is pushed back along -x by the water (thrust), so its
centre leaves the mounting point towards -x; the drive's work, integral of T w dt, equals the work
the structure did on the fluid (run.json energy audit) within 5 % (the rest: the mount's spring
and the carrier's energies); analyze.py draws the run. The flux against three rates is
run_rates.py's (docs/validation.md); a second coupled run here would cost the suite another
minute."""
import os
import subprocess
import sys

from fsi_test import binary, check, cleanup, example, manifest, work_dir, ENV

sys.path.insert(0, os.path.dirname(example("rotor", "analyze.py")))
sys.path.insert(0, os.path.dirname(os.path.dirname(example("rotor", "analyze.py"))))
from analyze import analyse  # noqa: E402

END = 0.09
output = work_dir("rotor")
run_dir = os.path.join(output, "rate_40")
command = [binary("fsi-run"), example("rotor", "rotor_coarse.scene"), "--np", "2", "--output", run_dir,
           "--set", f"Resolution.end_time={END}",
           "--set", "Rotor.rate=40"]
result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=900)
if result.returncode != 0:
    print(result.stderr[-4000:])
check(result.returncode == 0, f"fsi-run exits 0 (got {result.returncode})")
record = manifest(run_dir)
check(record["status"] == "completed", "run.json says completed")
checks = record["checks"]
check(checks["particles_final"] == checks["particles_initial"], "no particle lost")
check(checks["max_action_reaction_relative"] <= 1e-12,
      f"action = reaction at every exchange ({checks['max_action_reaction_relative']:.3e})")

r = analyse(run_dir)[0]
up, down = r["flux_upstream"], r["flux_downstream"]
print(f"measured: flux upstream {1e6 * up:.3f}, downstream {1e6 * down:.3f} cm^3/s over t >= "
      f"{r['window_start']:.4f} s; thrust {1e3 * r['thrust_mean']:.3f} mN; centre mean dx "
      f"{1e6 * r['centre_mean_displacement']['x']:+.1f} um; drive work {1e3 * r['drive_work']:.4f} mJ, "
      f"work on the fluid {1e3 * r['work_structure_on_fluid']:.4f} mJ")
# A mean speed of 1 mm/s through the 0.03 x 0.027 m section: 0.81 cm^3/s (the run reaches ~10).
check(up > 8.1e-7 and down > 8.1e-7, f"the rotor pumps towards +x at both probes ({up:.3e}, {down:.3e} m^3/s)")
check(r["thrust_mean"] > 0, f"the water pushes the rotor along -x (thrust {r['thrust_mean']:.3e} N > 0)")
check(r["centre_mean_displacement"]["x"] < 0,
      f"the thrust moves the centre towards -x ({r['centre_mean_displacement']['x']:.3e} m)")
check(r["drive_torque_mean"] > 0, f"the drive turns the rotor against the water ({r['drive_torque_mean']:.3e} N m)")
balance = abs(r["drive_work"] / r["work_structure_on_fluid"] - 1)
check(balance < 0.05, f"the drive's work is the structure's work on the fluid ({100 * balance:.2f} % < 5 %)")

result = subprocess.run([sys.executable, example("rotor", "analyze.py"), run_dir,
                         "--figure-prefix", os.path.join(output, "rotor")],
                        capture_output=True, text=True, timeout=120)
print(result.stdout[-3000:], result.stderr[-2000:])
check(result.returncode == 0, "analyze.py reads the run")
for figure in ("rotor_flux.png", "rotor_trajectory.png", "rotor_hub.png"):
    path = os.path.join(output, figure)
    check(os.path.isfile(path) and os.path.getsize(path) > 10000, f"analyze.py drew {figure}")
cleanup(output)
print("PASS")
