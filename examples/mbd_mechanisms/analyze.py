#!/usr/bin/python3
"""Checks an `fsi-server --mbd-only` run of mbd_mechanisms.scene (DIR/sensors.csv) against the
closed forms in README.md: the block on the 30-degree incline, the torsion wheel, the valve on
its one-sided spring actor, the rotor in its one-sided torsion stop, and the conservation of
kinetic + potential energy.
Prints one line per check; exit status 1 if one fails."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import Checks, read_sensors  # noqa: E402 (examples/fsi_results.py)

G = 9.81


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: analyze.py RUN_DIR")
    s = read_sensors(sys.argv[1] + "/sensors.csv")
    t = s["time"]
    checks = Checks()
    check = checks.check

    angle = math.radians(30.0)
    along = -0.5 * G * math.sin(angle) * t[-1] ** 2
    check("block x at t = 1 s [m]", s["block_x"][-1], along * math.cos(angle), 1e-9)
    check("block y at t = 1 s [m]", s["block_y"][-1], along * math.sin(angle), 1e-9)
    normal = 2.0 * G * math.cos(angle)
    # Multipliers carry the index-3 round-off floor of the Newton test (~eps M |q| / h^2).
    check("incline force x [N/m]", s["incline_force_x"][-1], -normal * math.sin(angle), 1e-5)
    check("incline force y [N/m]", s["incline_force_y"][-1], normal * math.cos(angle), 1e-5)
    check("wheel angle at t = 1 s [rad]", s["wheel_angle"][-1], 0.2 * math.cos(6.0 * t[-1]), 1e-9)
    check("torsion torque at t = 1 s [N m/m]", s["torsion_torque"][-1], -9.0 * s["wheel_angle"][-1], 1e-12)
    check("axle force y [N/m]", max(abs(f - G) for f in s["axle_force_y"]) + G, G, 1e-9)

    # The valve falls 5 cm, is stopped by 5000 N/m and flies back up: period 2 sqrt(2 h / g) plus
    # the half oscillation of the contact (README.md).
    mass, k, h = 0.1, 5000.0, 0.05
    compression = (mass * G + math.sqrt((mass * G) ** 2 + 2.0 * k * mass * G * h)) / k
    check("lowest valve y [m] (sampled every 1 ms)", min(s["valve_y"]), 0.05 - compression, 2e-5)
    check("largest push of the stop [N/m] (sampled)", min(s["stop_tension"]), -k * compression, 0.2)
    onsets = [t[i] for i in range(1, len(t)) if s["stop_tension"][i] < 0.0 <= s["stop_tension"][i - 1]]
    check("first contact [s]", onsets[0], math.sqrt(2.0 * h / G), 1.5e-3)
    check("bounce period [s]", onsets[1] - onsets[0], 0.2163730634, 2e-3)
    highest = max(s["valve_y"][i] for i in range(len(t)) if t[i] > 0.12 and t[i] < 0.3)
    check("valve back at its height [m]", highest, 0.1, 1e-4)

    # The rotor (J = 0.25) turns at 2 rad/s from -0.2 rad into the stop at 0: a half oscillation
    # of sqrt(k / J) inside it, out again at -2 rad/s.
    inertia, spin, latch = 0.25, 2.0, 100.0
    reach = spin * math.sqrt(inertia / latch)
    inside = math.pi * math.sqrt(inertia / latch)
    out = 0.2 / spin + inside
    # Sampled every 1 ms: the peak is missed by at most reach (1 - cos(omega * 0.5 ms)) = 5e-6.
    check("rotor's deepest turn [rad] (sampled)", max(s["rotor_angle"]), reach, 1e-5)
    check("largest torque of the stop [N m/m] (sampled)", min(s["latch_torque"]), -latch * reach,
          1e-3)
    touching = [t[i] for i in range(len(t)) if s["latch_torque"][i] < 0.0]
    check("time in the stop [s] (sampled every 1 ms)", touching[-1] - touching[0], inside, 2e-3)
    check("rotor angle at t = 1 s [rad]", s["rotor_angle"][-1], -spin * (t[-1] - out), 1e-6)

    energy = [a + b for a, b in zip(s["kinetic_energy"], s["potential_energy"])]
    start = 0.5 * 9.0 * 0.2 ** 2 + mass * G * 0.1 + 0.5 * inertia * spin ** 2
    check("energy drift max |E - E0| [J/m]", max(abs(e - start) for e in energy), 0.0, 1e-5)
    checks.exit(count=True)


if __name__ == "__main__":
    main()
