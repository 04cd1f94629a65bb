#!/usr/bin/python3
"""The server's progress report on a short coarse static tank (a snapshot every 250 steps):
without a terminal, periodic log lines on stderr and in DIR/fsi-server.log with simulated time,
percent, steps/s, ETA, the closest wall approach in r0 and the latest snapshot's max |rho/rho0-1|
and max speed against the speed of sound (the scene's cAB = 20 m/s); the last line says 100 %.
With stderr on a terminal (a pty), a live status line rewritten in place ("\\r" + erase to end of
line), the same numbers, and the log file still gets the periodic lines. The log file is flushed line by line:
while the run goes on it holds every progress line stderr has shown."""
import os
import pty
import re
import select
import subprocess
import time

from fsi_test import (ENV, binary, check, cleanup, example, fail, kill_group, read, start_client, start_server,
                      wait, work_dir)

SCENE = example("static_tank", "static_tank_coarse.scene")
OVERRIDES = ["Resolution.end_time=1000*1e-5", "Resolution.equilibration_steps=500",
             "Resolution.snapshot_every_steps=250"]
LINE = re.compile(r"t = (\d\.\d{4})/0\.0100 s \((\d+\.\d) %\), (\d+) steps/s, ETA (\d+:\d\d:\d\d) \| "
                  r"closest wall (\d+\.\d\d) r0 \| snapshot t = (\d\.\d{4}) s: max \|rho/rho0-1\| (\S+), "
                  r"max speed (\S+) m/s = (\S+) c")


def check_lines(lines, where):
    check(len(lines) >= 2, f"{where}: {len(lines)} progress lines with every number")
    for line in lines:
        match = LINE.search(line)
        time_now, percent, rate, _, closest, snapshot, deviation, speed, ratio = match.groups()
        # t is shown to 0.1 ms: 0.5 % of the 10 ms run, plus the percent's own rounding.
        if abs(float(percent) - 100.0 * float(time_now) / 0.01) > 0.55:
            fail(f"{where}: percent {percent} does not match t = {time_now} of 0.01 s: {line}")
        if not (0.1 < float(closest) < 2.0 and 0.0 < float(deviation) < 0.05 and int(rate) > 0):
            fail(f"{where}: implausible numbers in {line}")
        if abs(float(ratio) - float(speed) / 20.0) > 0.01 * float(ratio):
            fail(f"{where}: speed/c {ratio} is not max speed {speed} / 20 m/s: {line}")
        if float(snapshot) > float(time_now) + 1e-12:
            fail(f"{where}: snapshot time {snapshot} after the current time {time_now}")
    check(LINE.search(lines[-1]).group(2) == "100.0", f"{where}: the last line says 100.0 %")


# --- not a terminal: periodic log lines ---
output = work_dir("progress")
run_dir = os.path.join(output, "log")
server, port = start_server(SCENE, run_dir, OVERRIDES, extra=["--progress-interval", "0.1"])
client = start_client(port, 2, run_dir)
# While the run goes on, a progress line on stderr is in fsi-server.log too (flushed per line: a
# log that stops mid-line reads as a hung run; a user saw that for minutes).
lagging, seen_running = [], 0
deadline = time.time() + 120
while server.poll() is None and time.time() < deadline:
    on_stderr = sum(1 for line in read(run_dir, "server.stderr").splitlines() if LINE.search(line))
    if on_stderr > 0:
        time.sleep(0.05)  # the file sink is written right after the console's
        in_log = sum(1 for line in read(run_dir, "fsi-server.log").splitlines() if LINE.search(line))
        if server.poll() is None:
            seen_running += 1
            if in_log < on_stderr:
                lagging.append((on_stderr, in_log))
    time.sleep(0.05)
status = wait(server, 1)
if status is None:
    kill_group(server)
    kill_group(client)
    fail("fsi-server did not finish within 120 s")
wait(client, 30)
check(seen_running >= 2 and not lagging,
      f"fsi-server.log kept up with stderr while the run went on ({seen_running} looks; behind: {lagging[:3]})")
stderr = read(run_dir, "server.stderr")
check(status == 0, f"fsi-server exits 0 (got {status})")
check("\r" not in stderr and "\x1b[" not in stderr, "no carriage returns or escape sequences without a terminal")
lines = [line for line in stderr.splitlines() if LINE.search(line)]
print("\n".join(lines[-3:]))
check_lines(lines, "stderr (not a terminal)")
log_lines = [line for line in read(run_dir, "fsi-server.log").splitlines() if LINE.search(line)]
check(len(log_lines) == len(lines), f"fsi-server.log has the same {len(lines)} progress lines")

# --- a terminal: the live line ---
run_dir = os.path.join(output, "tty")
os.makedirs(run_dir)
port_file = os.path.join(run_dir, "port")
master, slave = pty.openpty()
command = [binary("fsi-server"), SCENE, "--output", run_dir, "--port", "0", "--port-file", port_file,
           "--progress-interval", "0.1"]
for item in OVERRIDES:
    command += ["--set", item]
server = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=slave, stderr=slave, env=ENV,
                          start_new_session=True)
os.close(slave)
captured = b""
client = None
deadline = time.time() + 120
while time.time() < deadline:
    if client is None and os.path.exists(port_file) and open(port_file).read().strip():
        client = start_client(int(open(port_file).read()), 2, run_dir)
    ready, _, _ = select.select([master], [], [], 0.2)
    if ready:
        try:
            chunk = os.read(master, 65536)
        except OSError:  # the server closed its end
            break
        if not chunk:
            break
        captured += chunk
    elif server.poll() is not None:
        break
status = wait(server, 10)
if client is not None:
    wait(client, 30)
os.close(master)
if status is None:
    kill_group(server)
    fail("fsi-server on a pty did not finish")
text = captured.decode(errors="replace")
check(status == 0, f"fsi-server on a terminal exits 0 (got {status})")
updates = text.split("\r\x1b[K")
live = [update.split("\n")[0] for update in updates[1:] if LINE.search(update.split("\n")[0])]
print(repr(updates[-1][:300]))
check(len(live) >= 2, f"the terminal got {len(live)} in-place updates of the status line")
check_lines(live, "live line")
check(re.search(r"100\.0 %[^\r\n]*\r?\n", text) is not None, "the final status line stays on the screen (ends with a newline)")
log_lines = [line for line in read(run_dir, "fsi-server.log").splitlines() if LINE.search(line)]
check(len(log_lines) >= 2 and "\r" not in read(run_dir, "fsi-server.log"),
      f"with a terminal, fsi-server.log still gets the {len(log_lines)} periodic progress lines, no \\r")
cleanup(output)
