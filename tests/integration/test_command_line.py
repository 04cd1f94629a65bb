#!/usr/bin/python3
"""Command line and logs of every program. `--help` of fsi-server, fsi-client, fsi-run and fsi-plot
lists every option with its default (CLI11's "=value", or "default" / "required" in the text) and
--log-level where it applies. fsi-run passes its --log-level to both sides and gives the client
DIR/fsi-client.log: rank 0 only by default, one file per rank with --log-all-ranks, and no info
lines at --log-level warn (fsi-server.log neither)."""
import os
import re
import subprocess

from fsi_test import ENV, binary, check, cleanup, example, fail, work_dir

SCENE = example("static_tank", "static_tank_coarse.scene")
SHORT = ["--set", "Resolution.end_time=100*Resolution.time_step", "--set", "Resolution.equilibration_steps=100",
         "--set", "Resolution.snapshot_every_steps=0"]


def help_text(program):
    command = [binary(program), "--help"]
    if program == "fsi-client":
        command = ["mpirun", "--allow-run-as-root", "-np", "1"] + command
    result = subprocess.run(command, capture_output=True, text=True, timeout=60, env=ENV)
    if result.returncode != 0:
        fail(f"{program} --help exits {result.returncode}: {result.stderr}")
    return result.stdout


def option_entries(text):
    """{option: its help entry} from CLI11 or argparse help: an entry starts with '  -' and
    continues on more deeply indented lines."""
    entries, current = {}, None
    for line in text.splitlines():
        match = re.match(r"^  (-[-\w, ]*?--[\w-]+|-\w|--[\w-]+)\b(.*)$", line)
        if match:
            current = match.group(1).split(",")[-1].strip().split(" ")[0]
            entries[current] = match.group(2)
        elif current and line.startswith("      ") and line.strip():
            entries[current] += " " + line.strip()
        elif not line.strip() or not line.startswith(" "):
            current = None
    return entries


for program, needs_log_level in (("fsi-server", True), ("fsi-client", True), ("fsi-run", True),
                                 ("fsi-plot", False)):
    entries = option_entries(help_text(program))
    check(len(entries) >= 8, f"{program} --help lists {len(entries)} options")
    for option, entry in entries.items():
        if option in ("--help", "--version"):
            continue
        if not re.search(r"=\S|default|required|REQUIRED", entry):
            fail(f"{program} --help: {option} does not state its default: {entry.strip()!r}")
    check(True, f"{program} --help: every option states its default")
    if needs_log_level:
        check("--log-level" in entries and "info" in entries["--log-level"],
              f"{program} has --log-level (default info)")

output = work_dir("command_line")


def run(name, *extra):
    run_dir = os.path.join(output, name)
    result = subprocess.run([binary("fsi-run"), SCENE, "--np", "2", "--output", run_dir, *SHORT, *extra],
                            capture_output=True, text=True, timeout=300, env=ENV)
    if result.returncode != 0:
        fail(f"fsi-run {' '.join(extra)} exits {result.returncode}:\n{result.stderr[-3000:]}")
    return run_dir


def text(run_dir, name):
    path = os.path.join(run_dir, name)
    if not os.path.exists(path):
        fail(f"{path} was not written; the folder holds {sorted(os.listdir(run_dir))}")
    with open(path) as handle:
        return handle.read()


run_dir = run("default")
client_log = text(run_dir, "fsi-client.log")
print(client_log)
check("[fsi-client rank 0] [info] connected to" in client_log and "run finished after 100 coupled steps" in client_log,
      "fsi-run gives the client DIR/fsi-client.log with rank 0's messages")
check("rank 1" not in client_log and not os.path.exists(os.path.join(run_dir, "fsi-client.log.rank1")),
      "by default only rank 0 logs")
check("[info]" in text(run_dir, "fsi-server.log"), "fsi-server.log has info lines at the default level")

run_dir = run("all_ranks", "--client-arg=--log-all-ranks")
rank1 = text(run_dir, "fsi-client.log.rank1")
print(rank1)
check(re.search(r"\[fsi-client rank 1\] \[info\] ready: \d+ of 1980 particles on this rank", rank1) is not None,
      "--log-all-ranks: rank 1 writes its own file fsi-client.log.rank1")
check("rank 1" not in text(run_dir, "fsi-client.log"), "rank 0's file has rank 0's lines only")

run_dir = run("warn", "--log-level", "warn")
check("[info]" not in text(run_dir, "fsi-client.log") and "[info]" not in text(run_dir, "fsi-server.log"),
      "--log-level warn reaches both programs: no info lines in either log")
cleanup(output)
