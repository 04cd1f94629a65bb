#!/usr/bin/python3
"""Pump-driven channel flow with two valves (thesis §6.5): what the pump delivers per cycle and
when its valves open.

  analyze.py RUN_DIR [--min-net F] [--max-backflow F] [--phase-lead F] [--min-phase F] [--figure PNG]

The piston's face moves as x = x0 + A (1 - cos(2 pi t / T)) (the scene's Geometry.A, Geometry.T):
the expansion (the face moving +x, drawing water in) is the first half of each cycle, the
compression the second. Per cycle k (t from k T to (k + 1) T), from the flux probes (clockwise
positive, m^2/s per unit depth), integrated by the trapezoidal rule:
  - net volume V = int Q dt, forward volume int max(Q, 0) dt and backflow int max(-Q, 0) dt
    through the inlet port (probe `inlet`), the riser above the outlet (`outlet`) and the bottom
    channel (`loop`); the net volume also relative to the piston's swept volume 2 A (ceiling -
    floor);
  - the valves' phases: the fraction of the expansion during which the inlet valve is open (its
    opening angle, minus the sensor inlet_angle, above 0.02 rad) and of the compression during
    which it is shut, and the same for the outlet valve (open: its free end more than 1 mm to the
    left of its rest) with the phases swapped; and the largest opening of each.
A valve opens when it passes its threshold and shuts when it falls below half of it (no flicker at
the threshold); each opening and shutting is listed with its time.
Checks (issue 14), over every cycle after the first: --min-net (net volume through the inlet and
through the outlet above this fraction of the swept volume; issue: > 0), --max-backflow (backflow
through each valve's probe below this fraction of its forward volume; issue: 0.2), --phase-lead
(each valve opens and shuts in the phases of thesis §6.5 — the inlet opens in the expansion and
shuts in the compression, the outlet the other way round — or earlier by at most this fraction
of the half period: the loop's water, slowed by the slowing piston, raises the chamber's
pressure before the piston turns), --min-phase (each valve open or shut
in its phase for at least this fraction of the phase). Without an option the figure is only
stated. --figure draws the piston, the valves and the fluxes."""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import finish_figure, pyplot, read_run, require_run, write_analysis  # noqa: E402

PROBES = ("inlet", "outlet", "loop")
OPEN_ANGLE = 0.02  # rad: the inlet valve counts as open above this
OPEN_TIP = 0.001  # m: the outlet valve counts as open when its free end is this far left of its rest


def integrate(times, values, start, end):
    """The trapezoidal integral of the samples within [start, end] (the samples' own times)."""
    total = 0.0
    for i in range(1, len(times)):
        a, b = times[i - 1], times[i]
        if a >= start - 1e-12 and b <= end + 1e-12:
            total += 0.5 * (values[i - 1] + values[i]) * (b - a)
    return total


def fraction(times, flags, start, end):
    """The time fraction of [start, end) in which `flags` holds (sample-and-hold)."""
    inside = total = 0.0
    for i in range(1, len(times)):
        a, b = times[i - 1], times[i]
        if a >= start - 1e-12 and b <= end + 1e-12:
            total += b - a
            inside += (b - a) if flags[i] else 0.0
    return inside / total if total > 0 else float("nan")


def valve_states(values, open_above):
    """Open/shut per sample with hysteresis: opens above `open_above`, shuts below half of it (a
    value hovering at the threshold does not flicker)."""
    states, is_open = [], False
    for v in values:
        if not is_open and v > open_above:
            is_open = True
        elif is_open and v < 0.5 * open_above:
            is_open = False
        states.append(is_open)
    return states


def events(times, states, start, end):
    """The (time, "opens" | "shuts") changes of `states` within (start, end]."""
    found = []
    for i in range(1, len(times)):
        if start < times[i] <= end + 1e-12 and states[i] != states[i - 1]:
            found.append((times[i], "opens" if states[i] else "shuts"))
    return found


def analyze(run_dir):
    require_run(run_dir, "pump")
    run, sensors = read_run(run_dir)
    p = run["parameters_flat"]
    period, amplitude = p["Geometry.T"], p["Geometry.A"]
    swept = 2.0 * amplitude * (p["Geometry.ceiling"] - p["Geometry.floor"])
    time = sensors["time"]
    if len(time) < 2:
        raise SystemExit(f"analyze: {run_dir}/sensors.csv holds {len(time)} row(s); the run stopped before its "
                         "first sensor rows (its fsi-server.log says why)")
    angle = [-a for a in sensors["inlet_angle"]]  # the opening: the flap turns clockwise (angle < 0) to open
    tip = [x - sensors["outlet_tip_x"][0] for x in sensors["outlet_tip_x"]]
    inlet_open = valve_states(angle, OPEN_ANGLE)
    outlet_open = valve_states([-d for d in tip], OPEN_TIP)
    cycles = []
    # Every whole period the run holds (its last sensor row may fall a sensor interval short).
    for k in range(int((time[-1] + 0.01 * period) / period)):
        start, middle, end = k * period, (k + 0.5) * period, (k + 1) * period
        cycle = {"cycle": k + 1, "start": start, "end": end}
        for name in PROBES:
            q = sensors[name + "_flux"]
            forward = integrate(time, [max(v, 0.0) for v in q], start, end)
            backward = integrate(time, [max(-v, 0.0) for v in q], start, end)
            cycle[name] = {"net": forward - backward, "forward": forward, "backflow": backward,
                           "net_of_swept": (forward - backward) / swept,
                           "backflow_of_forward": backward / forward if forward > 0 else float("inf")}
        in_cycle = [i for i, t in enumerate(time) if start <= t <= end]
        cycle["inlet_open_in_expansion"] = fraction(time, inlet_open, start, middle)
        cycle["inlet_shut_in_compression"] = fraction(time, [not f for f in inlet_open], middle, end)
        cycle["outlet_open_in_compression"] = fraction(time, outlet_open, middle, end)
        cycle["outlet_shut_in_expansion"] = fraction(time, [not f for f in outlet_open], start, middle)
        # When each valve opens and shuts, and whether in its phase (thesis §6.5: the inlet opens in
        # the expansion and shuts in the compression, the outlet the other way round).
        cycle["inlet_events"] = events(time, inlet_open, start, end)
        cycle["outlet_events"] = events(time, outlet_open, start, end)
        # The lead: how long before its phase an event came (0 inside it; the loop's water, slowed
        # by the slowing piston, raises the chamber's pressure before the piston turns).
        def lead(t, phase_start, phase_end):
            if phase_start <= t <= phase_end:
                return 0.0
            return (phase_start - t) if t < phase_start else (phase_start + period - t)
        expansion, compression = (start, middle), (middle, end)
        cycle["events"] = (
            [("inlet", t, what, lead(t, *(expansion if what == "opens" else compression)))
             for t, what in cycle["inlet_events"]] +
            [("outlet", t, what, lead(t, *(compression if what == "opens" else expansion)))
             for t, what in cycle["outlet_events"]])
        cycle["inlet_max_angle"] = max(angle[i] for i in in_cycle)
        cycle["outlet_max_opening"] = -min(tip[i] for i in in_cycle)
        cycles.append(cycle)
    return {"run_dir": run_dir, "spacing": p["Fluid.spacing"], "period": period, "swept_volume": swept,
            "end_time": time[-1], "cycles": cycles,
            "series": {"time": time, "piston_x": sensors["piston_x"], "inlet_angle": angle, "outlet_tip": tip,
                       **{name: sensors[name + "_flux"] for name in PROBES}}}


def report(result):
    print(f"pump, d = {1000 * result['spacing']:g} mm, T = {result['period']:g} s, swept volume "
          f"{1e4 * result['swept_volume']:.2f} cm^2 per cycle (per unit depth), t = 0-{result['end_time']:.3g} s "
          f"({result['run_dir']}):")
    print("  cycle | net volume [cm^2 per unit depth] inlet / riser / bottom channel (of the swept volume) | "
          "backflow / forward: inlet, riser, channel | inlet valve open in the expansion, shut in the compression | "
          "outlet valve open in the compression, shut in the expansion | largest opening: inlet angle, outlet's end")
    for c in result["cycles"]:
        nets = " / ".join(f"{1e4 * c[n]['net']:+.2f} ({100 * c[n]['net_of_swept']:+.0f} %)" for n in PROBES)
        backs = ", ".join(f"{100 * c[n]['backflow_of_forward']:.0f} %" for n in PROBES)
        print(f"  {c['cycle']} | {nets} | {backs} | {100 * c['inlet_open_in_expansion']:.0f} %, "
              f"{100 * c['inlet_shut_in_compression']:.0f} % | {100 * c['outlet_open_in_compression']:.0f} %, "
              f"{100 * c['outlet_shut_in_expansion']:.0f} % | {c['inlet_max_angle']:.3f} rad, "
              f"{1000 * c['outlet_max_opening']:.1f} mm")
        ev = "; ".join(f"{name} {what} {t:.3f} s" + (f" ({1000 * ahead:.0f} ms before its phase)" if ahead else "")
                       for name, t, what, ahead in c["events"])
        print(f"      valves: {ev or 'no change'} (compression from {c['start'] + 0.5 * result['period']:.2f} s)")


def judge(result, args):
    failures = []
    later = result["cycles"][1:]
    if not later:
        failures.append(f"the run ends at t = {result['end_time']:.3f} s: no cycle after the first to judge")
    for c in later:
        for name in ("inlet", "outlet"):
            if args.min_net is not None and not c[name]["net_of_swept"] > args.min_net:
                failures.append(f"cycle {c['cycle']}: net volume through the {name} "
                                f"{100 * c[name]['net_of_swept']:+.1f} % of the swept volume, not above "
                                f"{100 * args.min_net:g} %")
            if args.max_backflow is not None and not c[name]["backflow_of_forward"] < args.max_backflow:
                failures.append(f"cycle {c['cycle']}: backflow through the {name} "
                                f"{100 * c[name]['backflow_of_forward']:.1f} % of the forward volume, not below "
                                f"{100 * args.max_backflow:g} %")
        if args.phase_lead is not None:
            failures += [f"cycle {c['cycle']}: the {name} valve {what} at t = {t:.3f} s, {1000 * ahead:.0f} ms "
                         f"({100 * ahead / (0.5 * result['period']):.0f} % of the half period) before its phase, "
                         f"more than {100 * args.phase_lead:g} %"
                         for name, t, what, ahead in c["events"] if ahead > args.phase_lead * 0.5 * result["period"]]
        if args.min_phase is not None:
            for key, what in (("inlet_open_in_expansion", "inlet valve open in the expansion"),
                              ("inlet_shut_in_compression", "inlet valve shut in the compression"),
                              ("outlet_open_in_compression", "outlet valve open in the compression"),
                              ("outlet_shut_in_expansion", "outlet valve shut in the expansion")):
                if not c[key] >= args.min_phase:
                    failures.append(f"cycle {c['cycle']}: {what} {100 * c[key]:.0f} % of the phase, below "
                                    f"{100 * args.min_phase:g} %")
    return failures


def draw(result, path):
    plt = pyplot("analyze.py")
    if plt is None:
        return
    s = result["series"]
    figure, (top, middle, bottom) = plt.subplots(3, 1, figsize=(7.2, 7.6), sharex=True)
    x0 = s["piston_x"][0]
    top.plot(s["time"], [1000 * (x - x0) for x in s["piston_x"]], "k", lw=1.2, label="piston [mm]")
    top.plot(s["time"], [1000 * d for d in s["outlet_tip"]], lw=1.2, label="outlet valve's free end, x [mm]")
    top.set_ylabel("displacement [mm]")
    middle.plot(s["time"], s["inlet_angle"], lw=1.2, color="C2", label="inlet valve's opening angle")
    middle.set_ylabel("angle [rad]")
    middle.grid(True, alpha=0.3)
    middle.legend(loc="upper left", fontsize=8)
    for name, label in (("inlet", "inlet port (+y)"), ("outlet", "riser (+y)"), ("loop", "bottom channel (-x)")):
        bottom.plot(s["time"], [1e3 * q for q in s[name]], lw=1.0, label=label)
    bottom.set_ylabel("volume flux [1e-3 m^2/s]")
    bottom.set_xlabel("t [s]")
    bottom.grid(True, alpha=0.3)
    bottom.legend(loc="upper left", fontsize=8)
    for axes in (top, middle, bottom):
        for c in result["cycles"]:
            axes.axvspan(c["start"] + 0.5 * result["period"], c["end"], color="0.92", zorder=0)
    finish_figure(figure, top, f"Pump with two valves, d = {1000 * result['spacing']:g} mm "
                               "(grey: compression)", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--min-net", type=float, help="fail if a later cycle's net volume through a valve, "
                                                      "over the swept volume, is not above this")
    parser.add_argument("--max-backflow", type=float, help="fail if a later cycle's backflow through a valve, "
                                                           "over its forward volume, is not below this")
    parser.add_argument("--min-phase", type=float, help="fail if a valve is open (shut) in its phase for less "
                                                        "than this fraction of it")
    parser.add_argument("--phase-lead", type=float,
                        help="fail if a valve opens or shuts earlier than its phase (the inlet opens in the expansion "
                             "and shuts in the compression, the outlet the other way round) by more than this "
                             "fraction of the half period")
    parser.add_argument("--figure", help="draw the piston, the valves and the fluxes (PNG)")
    args = parser.parse_args()
    result = analyze(args.run_dir)
    report(result)
    failures = judge(result, args)
    write_analysis(args.run_dir, {k: v for k, v in result.items() if k != "series"})
    if args.figure:
        draw(result, args.figure)
    for failure in failures:
        print(f"FAIL: {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
