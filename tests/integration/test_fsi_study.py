#!/usr/bin/python3
"""fsi-study (issue 15): a sweep over an --mbd-only pendulum (a link on a revolute joint, a bob on
a spring) over the time step and the Radau IIA stages, with one point that fails (Newton allowed
one iteration). The error of a point is the drift of kinetic + potential energy over the run,
relative to the swing's kinetic energy (an analyze script of this test: fsi-study takes any
script that writes analysis.json). Checked: study.csv has a row per point with the error, the
cost and the failed point's reason; the Pareto front is cheapest-first and no point beats a
front point in both; the cheapest point meeting a target is printed; a second call runs nothing
(resume), --retry-failed runs the failed point again; a target no point meets exits 3; bad
study files (and values the scene refuses, checked before any point runs) exit 2 with what, where
and how to fix, and run nothing."""
import csv
import json
import os
import subprocess

from fsi_test import SPRING_PENDULUM, ENV, binary, check, cleanup, work_dir

SCENE = SPRING_PENDULUM + "SolverOptions { end_time = 1.0; Timeint { step_size = 1e-3 } }\n"

ANALYZE = '''import csv, json, os, sys
run = sys.argv[1]
rows = [r for r in csv.reader(l for l in open(os.path.join(run, "sensors.csv")) if not l.startswith("#"))]
header, data = rows[0], [[float(v) for v in r] for r in rows[1:]]
k, p = header.index("kinetic"), header.index("potential")
energy = [r[k] + r[p] for r in data]
swing = max(r[k] for r in data)
json.dump({"energy": {"drift": (energy[-1] - energy[0]) / swing}}, open(os.path.join(run, "analysis.json"), "w"))
'''

output = work_dir("fsi_study")
for name, text in (("pendulum.scene", SCENE), ("energy.py", ANALYZE)):
    with open(os.path.join(output, name), "w") as handle:
        handle.write(text)
STUDY = {"format": "fsi-study", "version": 1, "scene": "pendulum.scene", "mode": "mbd-only",
         "grid": {"SolverOptions.Timeint.step_size": [0.04, 0.02, 0.01, 0.005],
                  "SolverOptions.Timeint.stages": [2, 3]},
         "points": [{"SolverOptions.Timeint.step_size": 0.01, "SolverOptions.Timeint.stages": 3,
                     "SolverOptions.Newton.max_iterations": 1}],
         "analyze": ["energy.py", "@RUN@"], "error": "energy.drift"}
study_file = os.path.join(output, "study.json")
with open(study_file, "w") as handle:
    json.dump(STUDY, handle)
study_dir = os.path.join(output, "study")


def fsi_study(*arguments, study=study_file):
    result = subprocess.run([binary("fsi-study"), study, "--output", study_dir] + list(arguments), env=ENV,
                            capture_output=True, text=True, timeout=600)
    print(result.stdout[-4000:], result.stderr[-2000:])
    return result


first = fsi_study("--jobs", "2", "--target", "1e-3")
check(first.returncode == 0, f"the study runs and meets 1e-3 (exit {first.returncode})")
check("9 points, 0 kept, 9 to run, 2 at a time" in first.stdout, "nine points: 4 x 2 on the grid and one listed")
with open(os.path.join(study_dir, "study.csv")) as handle:
    rows = list(csv.DictReader(handle))
check(len(rows) == 9, f"study.csv has a row per point ({len(rows)})")
done = [r for r in rows if r["status"] == "done"]
failed = [r for r in rows if r["status"] == "failed"]
check(len(done) == 8 and len(failed) == 1, f"8 points done, 1 failed ({len(done)}, {len(failed)})")
check(failed[0]["SolverOptions.Newton.max_iterations"] == "1" and "Newton" in failed[0]["reason"],
      f"the failed point is the one-iteration Newton, with the run's reason: {failed[0]['reason'][:200]}")
check(all(float(r["core_seconds"]) > 0 and int(r["steps"]) > 0 for r in done), "every done point has its cost")
errors = {(float(r["SolverOptions.Timeint.step_size"]), int(r["SolverOptions.Timeint.stages"])): float(r["error"])
          for r in done}
check(errors[(0.005, 3)] < errors[(0.04, 3)] and errors[(0.005, 2)] < errors[(0.04, 2)],
      f"the energy drift falls with the step: {errors}")
front = sorted((float(r["core_seconds"]), float(r["error"])) for r in done if r["pareto"] == "yes")
check(len(front) >= 1 and all(r["pareto"] == "no" for r in failed), f"the front has points, no failed one: {front}")
check([e for _, e in front] == sorted((e for _, e in front), reverse=True), "along the front the error falls with cost")
by_cost = sorted((float(r["core_seconds"]), float(r["error"])) for r in done)
for cost, error in front:
    check(not any(c <= cost and e < error for c, e in by_cost),
          f"no point is as cheap and more accurate than the front point ({cost:.4g} core-s, {error:.4g})")
for cost, error in by_cost:
    check(any(c <= cost and e <= error for c, e in front), f"the point ({cost:.4g}, {error:.4g}) is matched by the front")
check("error <= 0.001: cheapest" in first.stdout, "the cheapest point meeting 1e-3 is printed")
check(os.path.getsize(os.path.join(study_dir, "pareto.png")) > 10_000, "pareto.png written")

# The grid of two parameters as a map: a row per step, a column per stage count, each cell the
# point's error as in study.csv.
with open(os.path.join(study_dir, "map.md")) as handle:
    table = [line.strip().strip("|").split("|") for line in handle if line.strip()]
check(len(table) == 2 + 4 and [c.strip() for c in table[0][1:]] == ["2", "3"],
      f"map.md: a header with the stages 2 and 3, a rule and 4 rows: {table}")
for row in table[2:]:
    step = float(row[0])
    for stages, cell in zip((2, 3), row[1:]):
        check(cell.strip() == f"{errors[(step, stages)]:.3g}", f"map.md cell dt = {step}, {stages} stages: {cell.strip()}")

again = fsi_study("--target", "1e-30")
check(again.returncode == 3, f"a target no point meets: exit 3 (got {again.returncode})")
check("9 kept, 0 to run" in again.stdout and "no point of the study meets it" in again.stdout,
      "a second call runs nothing and says the target is not met")
retry = fsi_study("--retry-failed")
check(retry.returncode == 0 and "8 kept, 1 to run" in retry.stdout, "--retry-failed runs only the failed point")

for name, change, where, fix in (
        ("unknown key", {"grids": {}}, "study_bad.json", "use the keys"),
        ("missing scene file", {"scene": "nope.scene"}, "study_bad.json: scene", "give an existing scene file"),
        ("a grid value that is not a number", {"grid": {"SolverOptions.Timeint.step_size": [0.01, True]}},
         "study_bad.json: grid.SolverOptions.Timeint.step_size[1]", "give a number"),
        # The scene checks every point's values before the first point runs.
        ("a text value without its quotes",
         {"grid": {"SolverOptions.Timeint.step_size": [0.01], "SolverOptions.Timeint.tableau": ["LobattoIIIA"]}},
         "study_bad.json", "with its quotes inside the JSON string")):
    bad = dict(STUDY, **change)
    bad_file = os.path.join(output, "study_bad.json")
    with open(bad_file, "w") as handle:
        json.dump(bad, handle)
    before = sorted(os.listdir(os.path.join(study_dir, "points")))
    result = fsi_study(study=bad_file)
    check(result.returncode == 2 and where in result.stderr and fix in result.stderr,
          f"{name}: exit 2, where ({where}) and how to fix")
    check(sorted(os.listdir(os.path.join(study_dir, "points"))) == before, f"{name}: nothing runs")
cleanup(output)
