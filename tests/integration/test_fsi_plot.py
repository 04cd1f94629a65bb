#!/usr/bin/python3
"""fsi-plot on a real short run (coarse static tank, a snapshot every 250 steps): one valid PNG of
non-trivial size per sensor, the stacked sensors.png, the example's declared figure
(examples/static_tank/fsi-plot.json) with N m g equal to run.json's counts, one frame per snapshot by default and one per
requested time with --frames; --mp4 makes an H.264 video of every snapshot that ffprobe decodes
(frame count), and says how to install ffmpeg when it is missing; a series' expression over sensors plots what
the sensor does, integral() and derivative() along time give the closed forms; a folder without sensors.csv is refused with what/where/how and a non-zero status; --help works."""
import json
import os
import struct
import subprocess

from fsi_test import binary, check, cleanup, example, fail, manifest, read, run_pair, work_dir

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def png_size(path):
    """(width, height) from the IHDR chunk, after checking the PNG signature."""
    with open(path, "rb") as handle:
        head = handle.read(24)
    if head[:8] != PNG_SIGNATURE or head[12:16] != b"IHDR":
        fail(f"{path} is not a PNG file")
    return struct.unpack(">II", head[16:24])


def check_png(path, min_bytes):
    if not os.path.exists(path):
        fail(f"{path} was not written")
    width, height = png_size(path)
    size = os.path.getsize(path)
    check(width >= 300 and height >= 300 and size >= min_bytes,
          f"{os.path.relpath(path, run_dir)}: PNG {width}x{height}, {size} bytes")


def fsi_plot(*arguments):
    return subprocess.run([binary("fsi-plot"), *arguments], capture_output=True, text=True, timeout=120)


output = work_dir("fsi_plot")
run_dir = os.path.join(output, "run")
server_status, client_status = run_pair(
    example("static_tank", "static_tank_coarse.scene"), run_dir, 2,
    overrides=["Resolution.end_time=1000*1e-5", "Resolution.equilibration_steps=500",
               "Resolution.snapshot_every_steps=250"], timeout=280)  # a hang guard under ctest's 300 s
if server_status != 0 or client_status != 0:
    fail(f"the run failed ({server_status}, {client_status}):\n{read(run_dir, 'server.stderr')[-3000:]}")

result = fsi_plot("--help")
check(result.returncode == 0 and "--frames" in result.stdout and "--color" in result.stdout,
      "fsi-plot --help lists --frames and --color")

version = fsi_plot("--version")
server_version = subprocess.run([binary("fsi-server"), "--version"], capture_output=True, text=True).stdout.strip()
check(version.returncode == 0 and version.stdout.strip() == f"fsi-plot {server_version}" and "git" in server_version,
      f"fsi-plot --version names the build's release and git revision: {version.stdout.strip()}")

result = fsi_plot(run_dir)
print(result.stdout, result.stderr)
check(result.returncode == 0, f"fsi-plot DIR exits 0 (got {result.returncode})")
with open(os.path.join(run_dir, "sensors.csv")) as handle:
    header = [line for line in handle if not line.startswith("#")][0].strip().split(",")
for name in header[1:]:
    check_png(os.path.join(run_dir, "plots", "sensors", f"{name}.png"), 10_000)
check_png(os.path.join(run_dir, "plots", "sensors.png"), 30_000)
# The energy audit of the coupled run (energy.csv): the works exchanged, in one figure, a row at
# every sensor row; the static tank's coupling creates no energy (zero to round-off).
check_png(os.path.join(run_dir, "plots", "energy.png"), 20_000)
with open(os.path.join(run_dir, "energy.csv")) as handle:
    energy_rows = [line.split(",")[0] for line in handle if not line.startswith("#")]
with open(os.path.join(run_dir, "sensors.csv")) as handle:
    sensor_rows = [line.split(",")[0] for line in handle if not line.startswith("#")]
check(energy_rows == sensor_rows, f"energy.csv has a row at every sensor row ({len(energy_rows)} and {len(sensor_rows)})")
audit = manifest(run_dir)["energy_audit"]
check(audit["exchanges"] == manifest(run_dir)["steps"], f"run.json audits every exchange: {audit}")
check(abs(audit["coupling_energy"]) <= 1e-12 and audit["injection_warning_step"] is None,
      f"the static tank's coupling energy is zero to round-off: {audit['coupling_energy']:.3e} J/m")
# The example's own figure, declared in examples/static_tank/fsi-plot.json (found through the scene
# path in run.json), with N m g from this run's counts.
check_png(os.path.join(run_dir, "plots", "static_tank.png"), 60_000)
run = manifest(run_dir)
weight = run["fluid"]["particle_count"] * run["fluid"]["particle_mass"] * abs(run["model"]["gravity"][1])
printed = [float(line.rsplit("=", 1)[1]) for line in result.stdout.splitlines()
           if line.startswith("fsi-plot: static_tank.png: reference 'N m g' =")]
check(len(printed) == 2 and all(abs(value - weight) <= 1e-12 * weight for value in printed),
      f"the declared reference N m g = {printed} equals particle_count * particle_mass * g = {weight!r} of run.json")
frames = sorted(os.listdir(os.path.join(run_dir, "plots", "frames")))
check(frames == [f"frame_{step:09d}.png" for step in (0, 250, 500, 750, 1000)], f"one frame per snapshot (t = 0 first): {frames}")
for frame in frames:
    # About 2 000 coloured particles: a frame with one particle and the walls has ~29 kB.
    check_png(os.path.join(run_dir, "plots", "frames", frame), 60_000)

chosen_dir = os.path.join(output, "chosen")
result = fsi_plot(run_dir, "--frames", "0.0024,0.0099", "--color", "pressure", "--output", chosen_dir)
check(result.returncode == 0, f"fsi-plot --frames --color pressure exits 0 (got {result.returncode}: {result.stderr})")
chosen = sorted(os.listdir(os.path.join(chosen_dir, "frames")))
check(chosen == ["frame_000000250.png", "frame_000001000.png"], f"--frames picks the nearest snapshots: {chosen}")

# --window: a close-up of a 2D run takes the window's shape (here four times as wide as high);
# a window that is no rectangle is refused before anything is written.
window_dir = os.path.join(output, "window")
result = fsi_plot(run_dir, "--frames", "0", "--window", "0,0.04,0,0.01", "--output", window_dir)
check(result.returncode == 0, f"fsi-plot --window exits 0 (got {result.returncode}: {result.stderr})")
width, height = png_size(os.path.join(window_dir, "frames", "frame_000000000.png"))
check(width > 1.8 * height, f"the close-up takes the window's shape: {width}x{height}")
for bad_window in ("0,0.04,0.01,0", "0,0.04,0", "a,b,c,d"):
    result = fsi_plot(run_dir, "--window", bad_window, "--output", os.path.join(output, "bad_window"))
    check(result.returncode == 2 and "--window" in result.stderr and "how to fix" in result.stderr,
          f"--window {bad_window} is refused with a hint (status {result.returncode}: {result.stderr.strip()})")
check(not os.path.exists(os.path.join(output, "bad_window")), "nothing is written for a refused --window")

# --mp4: every snapshot's frame in an H.264 file that ffprobe decodes frame by frame.
movie_dir = os.path.join(output, "movie")
result = fsi_plot(run_dir, "--mp4", "--max-frames", "2", "--output", movie_dir)
check(result.returncode == 0, f"fsi-plot --mp4 exits 0 (got {result.returncode}: {result.stderr})")
movie = os.path.join(movie_dir, "frames.mp4")
check(os.path.exists(movie) and os.path.getsize(movie) > 10_000, f"frames.mp4 written ({os.path.getsize(movie)} bytes)")
probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                        "stream=codec_name,nb_read_frames,width,height", "-of", "json", movie],
                       capture_output=True, text=True, timeout=60)
stream = json.loads(probe.stdout)["streams"][0]
print(stream)
check(probe.returncode == 0 and stream["codec_name"] == "h264" and int(stream["nb_read_frames"]) == 5,
      f"ffprobe decodes {stream.get('nb_read_frames')} H.264 frames = the 5 snapshots (--max-frames does not cap it)")
check(stream["width"] >= 300 and stream["height"] >= 300, f"video is {stream['width']}x{stream['height']}")
no_ffmpeg = subprocess.run([binary("fsi-plot"), run_dir, "--mp4", "--output", os.path.join(output, "none")],
                           capture_output=True, text=True, timeout=120, env=dict(os.environ, PATH="/nonexistent"))
print(no_ffmpeg.stderr)
check(no_ffmpeg.returncode == 2 and "ffmpeg is not installed" in no_ffmpeg.stderr and
      "apt-get install ffmpeg" in no_ffmpeg.stderr, "without ffmpeg on PATH: exit 2, says so and how to install it")
check(not os.path.exists(os.path.join(output, "none")), "nothing is rendered when ffmpeg is missing")

# A declaration with a sensor the run does not have: refused, naming the file and the entry.
bad = os.path.join(output, "bad.json")
with open(bad, "w") as handle:
    json.dump({"format": "fsi-plot-figures", "version": 1, "figures": [{"file": "x.png", "panels": [
        {"series": [{"sensor": "bottom_fluid_force_y"}], "references": [{"value": "N*m*gravity"}]}]}]}, handle)
result = fsi_plot(run_dir, "--no-frames", "--figures", bad, "--output", os.path.join(output, "bad"))
print(result.stderr)
check(result.returncode == 2 and f"{bad}: figures[0].panels[0].references[0].value" in result.stderr and
      "unknown name 'gravity'" in result.stderr and "how to fix" in result.stderr,
      "an unknown name in a declared reference: exit 2 with file, entry and the names to use")

# A series' "expression" combines sensors (and the run's values): the same curve written two ways
# gives the same mean; an unknown name lists the sensors; a series with both or neither is refused.
def declared_series(name, *series):
    path = os.path.join(output, f"{name}.json")
    with open(path, "w") as handle:
        json.dump({"format": "fsi-plot-figures", "version": 1, "figures": [{"file": f"{name}.png", "panels": [
            {"series": list(series), "references": [{"value": "N*m*g", "label": "Nmg", "window": [0, "t_end/2"]}]}]}]},
                  handle)
    return fsi_plot(run_dir, "--no-frames", "--figures", path, "--output", os.path.join(output, name))


result = declared_series("expression", {"sensor": "bottom_fluid_force_y", "scale": -1, "label": "sensor"},
                         {"expression": "-(2*bottom_fluid_force_y - bottom_fluid_force_y) + 0*time*g",
                          "label": "expression"})
print(result.stdout, result.stderr)
means = {}
for line in result.stdout.splitlines():
    for label in ("sensor", "expression"):
        if f"mean of '{label}'" in line:
            means[label] = line.split(" = ")[-1]
check(result.returncode == 0 and len(means) == 2 and means["sensor"] == means["expression"]
      and 0.5 < float(means["sensor"].split(" x ")[0]) < 1.5,
      f"an expression over a sensor plots the sensor's curve: means {means}")
# integral() and derivative() along sensors.csv's time: the integral of t is t^2/2 (trapezoids are
# exact for it), the piston driven at v0 has the rate -v0; the window's means are those of the
# closed forms (a sum without the rows' time steps, or a difference quotient without them, is not).
def window_means(result, labels):
    means = {}
    for line in result.stdout.splitlines():
        for label in labels:
            if f"mean of '{label}'" in line:
                means[label] = line.split(" = ")[-1]
    return means


# (Scaled to print their digits beside N m g: the run lasts 0.01 s.)
result = declared_series("along_time", {"expression": "1e6*integral(time)", "label": "integral"},
                         {"expression": "1e6*time*time/2", "label": "t^2/2"},
                         {"expression": "-1000*derivative(piston_position_y)", "label": "rate"},
                         {"expression": "1000*Geometry.piston_v0 + 0*time", "label": "v0"})
print(result.stdout, result.stderr)
means = window_means(result, ("integral", "t^2/2", "rate", "v0"))
check(result.returncode == 0 and len(means) == 4 and means["integral"] == means["t^2/2"]
      and means["rate"] == means["v0"] and float(means["t^2/2"].split(" x ")[0]) > 0.1
      and float(means["v0"].split(" x ")[0]) > 1,
      f"integral(time) = t^2/2 and -derivative(piston_position_y) = v0 over the window: {means}")
result = declared_series("integral_args", {"expression": "integral(time, time)"})
check(result.returncode == 2 and "integral() takes one argument" in result.stderr,
      f"integral() with two arguments is refused: {result.stderr[-300:]}")
path = os.path.join(output, "integral_number.json")
with open(path, "w") as handle:
    json.dump({"format": "fsi-plot-figures", "version": 1, "figures": [{"file": "n.png", "panels": [
        {"series": [{"sensor": "bottom_fluid_force_y"}], "references": [{"value": "integral(N)"}]}]}]}, handle)
result = fsi_plot(run_dir, "--no-frames", "--figures", path, "--output", os.path.join(output, "integral_number"))
check(result.returncode == 2 and "integral() works along sensors.csv's time" in result.stderr
      and "figures[0].panels[0].references[0]" in result.stderr,
      f"integral() in a number of the declaration is refused with the entry: {result.stderr[-300:]}")

result = declared_series("unknown", {"expression": "bottom_fluid_force_y - bottom_fluid_force_z"})
print(result.stderr)
check(result.returncode == 2 and "figures[0].panels[0].series[0].expression" in result.stderr
      and "unknown name 'bottom_fluid_force_z'" in result.stderr and "piston_position_y" in result.stderr,
      "an unknown name in an expression: exit 2 with the entry and the sensors it could use")
result = declared_series("both", {"sensor": "bottom_fluid_force_y", "expression": "bottom_fluid_force_y"})
check(result.returncode == 2 and "a series needs a \"sensor\" or an \"expression\", one of them" in result.stderr,
      "a series with a sensor and an expression is refused")

# "change": true plots the change since the first row; anything but a boolean is refused.
for change, status in ((True, 0), ("yes", 2)):
    declared = os.path.join(output, "change.json")
    with open(declared, "w") as handle:
        json.dump({"format": "fsi-plot-figures", "version": 1, "figures": [{"file": "change.png", "panels": [
            {"series": [{"sensor": "bottom_fluid_force_y", "change": change}]}]}]}, handle)
    result = fsi_plot(run_dir, "--no-frames", "--figures", declared, "--output", os.path.join(output, "change"))
    print(result.stderr)
    check(result.returncode == status, f"\"change\": {change!r} exits {status} (got {result.returncode})")
check("figures[0].panels[0].series[0]" in result.stderr and "not true or false" in result.stderr,
      "a \"change\" that is not a boolean: the entry and what it must be")

empty = os.path.join(output, "empty")
os.makedirs(empty)
result = fsi_plot(empty)
print(result.stderr)
check(result.returncode != 0, f"a folder without sensors.csv is refused (status {result.returncode})")
check("no sensors.csv" in result.stderr and empty in result.stderr and "how to fix" in result.stderr,
      "the message says what is missing, where, and how to fix it")
check(not os.path.exists(os.path.join(empty, "plots")), "nothing is written for a refused folder")
cleanup(output)
