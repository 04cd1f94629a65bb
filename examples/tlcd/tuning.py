#!/usr/bin/python3
"""The TLCD's tuning study (issue 14): the same building with the damper filled to several levels
around the tuned one. A fill level sets the column's length L = 2 (fill - b/2) + D and so its
period 2 pi sqrt(L / (2 g)); the building's period barely moves (the water is 8 % of its mass).
TLCD theory (as a tuned mass damper's, Den Hartog) says the damping peaks near the fill whose
column period matches the building's; away from it the water swings out of phase and damps less.

  tuning.py [--scene tlcd_coarse.scene] [--output out/tlcd_tuning] [--np 2] [--end-time T]
            [--fills 0.08,0.11,0.125,0.14,0.155,0.17,0.185,0.20] [--cycles 4]

Runs, each skipped when its folder already holds a completed run:
  OUTPUT/empty                the building with the empty damper (fsi-server --mbd-only)
  OUTPUT/fill_<f>/lumped      the building with that fill's water as a rigid mass on its top
                              (--mbd-only, Geometry.lumped_water = 1): the building's period
  OUTPUT/fill_<f>/run         the coupled run (fsi-run --set Geometry.fill=<f>)
then analyze.py on each coupled run against the empty building. Writes OUTPUT/tuning.md (a row per
fill: the column's and the building's periods by the runs above and by theory, their ratio, the
damping ratio by both of analyze.py's measures and its ratio to the empty building's; where the
damping is largest, in the runs and in linear_model.py's model with the same building periods) and
OUTPUT/tuning.png (the damping ratio against the fill, runs and model). Exit status 1 when a run
failed (its fsi-server.log says why) or when the damping is largest at an end of the range (the
fills do not bracket the optimum)."""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from fsi_results import completed, finish_figure, fsi_run_binary, pyplot, run_variant, study_arguments  # noqa: E402

import linear_model  # noqa: E402


def mbd_only(fsi_server, scene, run_dir, settings):
    """fsi-server --mbd-only of `scene` into `run_dir` with `settings` as --set, unless done before."""
    if completed(run_dir):
        return True
    command = [fsi_server, scene, "--mbd-only", "--output", run_dir, "--overwrite"]
    for name, value in settings:
        command += ["--set", f"{name}={value!r}"]
    print(" ".join(command), flush=True)
    return subprocess.run(command, stdout=subprocess.DEVNULL).returncode == 0


def analyze(run_dir, extra):
    """analyze.py on `run_dir` (printing what it prints); its analysis.json, or None."""
    subprocess.run([sys.executable, os.path.join(HERE, "analyze.py"), run_dir, *extra])
    try:
        with open(os.path.join(run_dir, "analysis.json")) as handle:
            return json.load(handle)
    except OSError:
        return None


def draw(path, rows, zeta_empty, dense, curves):
    """The damping ratio against the fill: the runs (both measures) and the linear model's curves
    (`curves[tilt]` over the fills `dense`)."""
    plt = pyplot("tuning.py")
    if plt is None:
        return
    figure, axes = plt.subplots(figsize=(7, 4.5))
    fills = [row["fill"] for row in rows]
    axes.plot(fills, [row["damping_ratio"] for row in rows], "ko-", label="coupled runs (decrement over 4 periods)")
    axes.plot(fills, [row["damping_ratio_least_squares"] for row in rows], "ks--", mfc="none",
              label="coupled runs (least squares)")
    for tilt, style, name in ((True, "b-", "translating and tilting top"), (False, "g-", "translating top (Sakai)")):
        axes.plot(dense, curves[tilt], style, linewidth=1, label=f"linear model, {name}")
    for row in rows:
        axes.annotate(f"{row['frequency_ratio']:.3f}", (row["fill"], row["damping_ratio"]),
                      textcoords="offset points", xytext=(4, -12), fontsize=7)
    axes.axhline(zeta_empty, color="r", label="empty damper")
    axes.axhline(3 * zeta_empty, color="r", linestyle="--", label="3x empty (issue 14)")
    axes.set_xlabel("fill [m] (numbers: frequency ratio column/building, linear theory's column)")
    axes.set_ylabel("damping ratio of the first mode")
    finish_figure(figure, axes, "TLCD tuning study", path, legend_location="best")
    plt.close(figure)


def main():
    parser = study_arguments(__doc__, os.path.join(HERE, "tlcd_coarse.scene"), os.path.join("out", "tlcd_tuning"))
    parser.add_argument("--fills", default="0.08,0.11,0.125,0.14,0.155,0.17,0.185,0.20", help="fill levels [m], comma-separated")
    parser.add_argument("--cycles", type=int, default=4)
    args = parser.parse_args()
    fills = linear_model.fill_levels(parser, args.fills)
    fsi_run = fsi_run_binary(args, "tuning.py")
    fsi_server = os.path.join(os.path.dirname(fsi_run), "fsi-server")
    common = [("Resolution.end_time", args.end_time)] if args.end_time is not None else []
    empty = os.path.join(args.output, "empty")
    failed = [] if mbd_only(fsi_server, args.scene, empty, common) else [empty]
    rows = []
    zeta_empty = None
    for fill in fills:
        folder = os.path.join(args.output, f"fill_{fill:g}")
        lumped, run = os.path.join(folder, "lumped"), os.path.join(folder, "run")
        settings = common + [("Geometry.fill", fill)]
        if not mbd_only(fsi_server, args.scene, lumped, settings + [("Geometry.lumped_water", 1)]):
            failed.append(lumped)
            continue
        if not run_variant(fsi_run, args.scene, run, args.np, settings):
            failed.append(run)
            continue
        building = analyze(lumped, ["--cycles", str(args.cycles)])
        result = analyze(run, ["--cycles", str(args.cycles), "--empty", empty])
        if building is None or result is None:
            failed.append(run)
            continue
        zeta_empty = result["damping_ratio_empty"]
        rows.append({"fill": fill, "column_period_theory": result["column_period_theory"],
                     "building_period": building["period"],
                     "frequency_ratio": building["period"] / result["column_period_theory"],
                     "damping_ratio": result["damping_ratio"],
                     "damping_ratio_least_squares": result["damping_ratio_least_squares"],
                     "damping_ratio_over_empty": result["damping_ratio_over_empty"],
                     "column_swing_max": result.get("column_swing_max")})
    if rows:
        rows.sort(key=lambda row: row["fill"])
        best = max(rows, key=lambda row: row["damping_ratio"])
        lines = ["| fill [m] | column period, theory [s] | building period, water lumped [s] | frequency ratio "
                 "column/building | damping ratio (decrement over 4 periods) | damping ratio (least squares) | x empty "
                 "| largest column swing [mm] |",
                 "|---|---|---|---|---|---|---|---|"]
        for row in rows:
            lines.append(f"| {row['fill']:g} | {row['column_period_theory']:.4f} | {row['building_period']:.4f} | "
                         f"{row['frequency_ratio']:.3f} | {row['damping_ratio']:.4f} | "
                         f"{row['damping_ratio_least_squares']:.4f} | "
                         f"{row['damping_ratio_over_empty']:.2f} | {1000 * row['column_swing_max']:.1f} |")
        lines.append("")
        best_fit = max(rows, key=lambda row: row["damping_ratio_least_squares"])
        lines.append(f"empty damper: damping ratio {zeta_empty:.4f}; the most damping at fill {best['fill']:g} m "
                     f"(frequency ratio {best['frequency_ratio']:.3f}; by least squares at {best_fit['fill']:g} m)")
        # The linear model with these building periods, every 2.5 mm of fill: its optimum here, its
        # curves in the figure.
        table = {row["fill"]: row["building_period"] for row in rows}
        dense = [rows[0]["fill"] + i * 0.0025 for i in range(int(round((rows[-1]["fill"] - rows[0]["fill"]) / 0.0025)) + 1)]
        curves = {tilt: [linear_model.model_damping(fill, table=table, tilt=tilt)[0] for fill in dense]
                  for tilt in (True, False)}
        for tilt, name in ((True, "translating and tilting top"), (False, "translating top")):
            model = dense[curves[tilt].index(max(curves[tilt]))]
            lines.append(f"the linear model (linear_model.py, {name}, the measured column, these building periods): "
                         f"the most damping at fill {model:.4g} m")
        if best in (rows[0], rows[-1]) and len(rows) > 2:
            failed.append(f"the study: the damping is largest at the end of the range, fill {best['fill']:g} m, so "
                          f"the fills do not bracket the optimum; add fills beyond it (--fills)")
        text = "\n".join(lines) + "\n"
        print(text)
        with open(os.path.join(args.output, "tuning.md"), "w") as handle:
            handle.write(text)
        draw(os.path.join(args.output, "tuning.png"), rows, zeta_empty, dense, curves)
    if failed:
        sys.exit(f"tuning.py: {len(failed)} failure(s): {'; '.join(failed)}")


if __name__ == "__main__":
    main()
