"""Helpers for integration tests that start the real fsi-server and `mpirun fsi-client`."""
import glob
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections import namedtuple

BIN = os.environ.get("FSI_BIN_DIR", "")
EXAMPLES = os.environ.get("FSI_EXAMPLES_DIR", "")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def protocol_version():
    """The protocol version this source tree speaks ("1.5"), read from protocol/version.hpp, for
    the tests that check a message naming it."""
    header = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "protocol", "include", "fsi",
                          "protocol", "version.hpp")
    with open(header) as handle:
        text = handle.read()
    numbers = [re.search(rf"k{part}Version = (\d+);", text) for part in ("Major", "Minor")]
    if not all(numbers):
        fail(f"no kMajorVersion/kMinorVersion in {header}")
    return f"{numbers[0].group(1)}.{numbers[1].group(1)}"


def binary(name):
    path = os.path.join(BIN, name)
    if not os.path.exists(path):
        fail(f"{path} is missing (FSI_BIN_DIR={BIN!r})")
    return path


def example(*parts):
    return os.path.join(EXAMPLES, *parts)


def fail(message):
    print(f"FAIL: {message}", flush=True)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)
    print(f"ok: {message}", flush=True)


def work_dir(name):
    path = tempfile.mkdtemp(prefix=f"fsi_{name}_")
    return path


def start_server(scene, output, overrides=(), extra=()):
    port_file = os.path.join(output, "port")
    os.makedirs(output, exist_ok=True)
    command = [binary("fsi-server"), scene, "--output", output, "--port", "0", "--port-file", port_file]
    for item in overrides:
        command += ["--set", item]
    command += list(extra)
    log = open(os.path.join(output, "server.stderr"), "w")
    process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=ENV, start_new_session=True)
    deadline = time.time() + 60
    while time.time() < deadline:
        if os.path.exists(port_file):
            with open(port_file) as handle:
                text = handle.read().strip()
            if text:
                return process, int(text)
        if process.poll() is not None:
            fail(f"fsi-server ended with {process.returncode} before listening:\n{read(output, 'server.stderr')}")
        time.sleep(0.05)
    process.kill()
    fail("fsi-server did not listen within 60 s")


def start_client(port, ranks, output, extra=()):
    # Not pinned: Open MPI would pin every test's rank 0 to core 0, where the tests that ctest
    # runs side by side would then queue (fsi-run passes the same by default).
    command = ["mpirun", "--oversubscribe", "--bind-to", "none", "-np", str(ranks)]
    if os.geteuid() == 0:
        command.append("--allow-run-as-root")
    command += [binary("fsi-client"), "--server", f"127.0.0.1:{port}"] + list(extra)
    log = open(os.path.join(output, "client.stderr"), "w")
    return subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=ENV, start_new_session=True)


def wait(process, timeout):
    try:
        return process.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        return None


def wait_for_exit(process, timeout, still_running):
    """Waits for a process that a fault should end; a process still running after `timeout` is
    killed and the test fails with the message `still_running`. Returns (status, seconds waited)."""
    started = time.time()
    status = wait(process, timeout)
    elapsed = time.time() - started
    if status is None:
        kill_group(process)
        fail(still_running)
    return status, elapsed


def start_client_for_fake_server(run_dir, ranks, extra=()):
    """Starts `mpirun fsi-client` against a socket of the test's own, which plays the server;
    returns the client process and the accepted connection."""
    os.makedirs(run_dir)
    with socket.socket() as listener:
        listener.bind(("127.0.0.1", 0))
        listener.listen(1)
        client = start_client(listener.getsockname()[1], ranks, run_dir, extra)
        listener.settimeout(30)
        connection, _ = listener.accept()
    return client, connection


def kill_group(process, sig=signal.SIGKILL):
    try:
        os.killpg(process.pid, sig)
    except ProcessLookupError:
        pass


def read(output, name):
    path = os.path.join(output, name)
    if not os.path.exists(path):
        return ""
    with open(path, errors="replace") as handle:
        return handle.read()


def static_tank_variant(directory, scene_name, appended):
    """The coarse static tank with `appended` added to its scene, written as `scene_name` into
    `directory` next to copies of the LIGGGHTS scripts and model file it includes."""
    os.makedirs(directory, exist_ok=True)
    for path in glob.glob(example("static_tank", "static_tank*.in*")) + [example("static_tank", "static_tank_model.inc")]:
        shutil.copy(path, directory)
    with open(example("static_tank", "static_tank_coarse.scene")) as handle:
        coarse = handle.read()
    scene = os.path.join(directory, scene_name)
    with open(scene, "w") as handle:
        handle.write(coarse + appended)
    return scene


def read_vtk(path, reader_class=None):
    """A VTK XML file read with VTK's own reader (unstructured grid unless told), failing the test
    when VTK cannot read it. VTK is imported here so that tests without VTK files need not have it."""
    import vtk
    reader = (reader_class or vtk.vtkXMLUnstructuredGridReader)()
    reader.SetFileName(path)
    if not reader.CanReadFile(path):
        fail(f"VTK's {type(reader).__name__} cannot read {path}")
    reader.Update()
    if reader.GetErrorCode() != 0:
        fail(f"VTK's reader reports error {reader.GetErrorCode()} on {path}")
    return reader.GetOutput()


def sensor_rows(output):
    text = read(output, "sensors.csv")
    return [line for line in text.splitlines() if line and not line.startswith("#")][1:]


def load_sensors(output):
    text = read(output, "sensors.csv")
    lines = [line for line in text.splitlines() if line and not line.startswith("#")]
    header = lines[0].split(",")
    columns = {name: [] for name in header}
    for line in lines[1:]:
        for name, value in zip(header, line.split(",")):
            columns[name].append(float(value))
    return columns


def manifest(output):
    with open(os.path.join(output, "run.json")) as handle:
        return json.load(handle)


def mbd_only_checked(scene, run_dir, overrides=(), timeout=300, label=""):
    """Runs `fsi-server SCENE --mbd-only` into run_dir with --set `overrides`; fails the test with
    its stderr unless it exits 0. Returns (sensors as columns, run.json)."""
    command = [binary("fsi-server"), scene, "--mbd-only", "--output", run_dir]
    for item in overrides:
        command += ["--set", item]
    result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=timeout)
    if result.returncode != 0:
        fail(f"{label or run_dir}: fsi-server --mbd-only exited {result.returncode}:\n{result.stderr[-3000:]}")
    return load_sensors(run_dir), manifest(run_dir)


def run_pair(scene, output, ranks, overrides=(), timeout=1200, client_args=()):
    """Runs server and client (with `client_args`) to completion; returns (server status, client
    status)."""
    server, port = start_server(scene, output, overrides)
    client = start_client(port, ranks, output, client_args)
    server_status = wait(server, timeout)
    if server_status is None:
        kill_group(server)
        kill_group(client)
        fail(f"fsi-server did not finish within {timeout} s")
    client_status = wait(client, 30)
    if client_status is None:
        kill_group(client)
        fail("fsi-client did not end within 30 s after the server")
    return server_status, client_status


# An --mbd-only scene of two bodies, a revolute joint and a spring (no fluid, no mesh): a link
# pivoting about the origin, a bob on a spring at its end, released horizontal; the energy
# sensors show how well the integrator keeps kinetic + potential. A test appends its own
# SolverOptions block (END_TIME, STEP) and sensors.
SPRING_PENDULUM = """scene_language = 1
Gravity { acceleration = [0, -9.81] }
RigidBody2D { name = "link"; mass = 1; inertia = 0.1; position = [0.5, 0] }
RigidBody2D { name = "bob"; mass = 0.5; inertia = 0.01; position = [1.5, 0] }
RevoluteJoint { name = "pivot"; body_a = "link"; point_a = [-0.5, 0] }
SpringDamper { name = "spring"; body_a = "link"; point_a = [0.5, 0]; body_b = "bob"; stiffness = 200; rest_length = 0.5 }
Sensor { name = "kinetic"; type = "kinetic_energy" }
Sensor { name = "potential"; type = "potential_energy" }
"""


ExampleRun = namedtuple("ExampleRun", "work run_dir run analysis")


def run_example_checked(scene, ranks, timeout, analyze_args=None, analyze_claim="", own_checks=None,
                        at_rest=None, label="", tail=3000, settings=()):
    """Runs the example `scene` (its folder and file under examples/, e.g. ("u_tube",
    "u_tube_coarse.scene")) with fsi-run on `ranks` ranks into "run" of a fresh work folder, and
    checks what every example test checks: fsi-run exits 0 (the last `tail` characters of its
    output printed), run.json says completed, no particle lost. Then the test's `own_checks(run)`
    of run.json (warnings, health, ...), then, with `at_rest` (its claim, e.g. "the column is at
    rest at release"), the release check. With `analyze_args`, the example's analyze.py
    runs on the run with them and must exit 0 (`analyze_claim` says what that means). `label`
    starts every message of these checks; `settings` ("Block.name=value") go to fsi-run as --set.
    Returns ExampleRun(work folder, run folder, run.json, analyze.py's completed process or None);
    the test calls cleanup(work) at its end."""
    folder, name = scene
    work = work_dir(os.path.splitext(name)[0])
    run_dir = os.path.join(work, "run")
    run = fsi_run_checked(example(folder, name), run_dir, ranks, settings=settings, timeout=timeout, label=label,
                          tail=tail)
    if own_checks:
        own_checks(run)
    if at_rest:
        check(run["release"]["at_rest"], f"{label}{at_rest}: {run['release'].get('warning')}")
    analysis = None
    if analyze_args is not None:
        analysis = subprocess.run(["/usr/bin/python3", example(folder, "analyze.py"), run_dir] + list(analyze_args),
                                  capture_output=True, text=True, timeout=300)
        print(analysis.stdout, analysis.stderr)
        check(analysis.returncode == 0, f"{label}{analyze_claim}")
    return ExampleRun(work, run_dir, run, analysis)


def fsi_run_checked(scene, run_dir, ranks, settings=(), timeout=900, label="", tail=None):
    """fsi-run of `scene` on `ranks` ranks into `run_dir` with every "Block.name=value" of `settings`
    given by --set; checks that it exits 0 (printing the last `tail` characters of its output, or the
    last 4000 when it fails), that run.json says completed and that no particle was lost. Returns
    run.json. `label` starts every message."""
    command = [binary("fsi-run"), scene, "--np", str(ranks), "--output", run_dir]
    for item in settings:
        command += ["--set", item]
    result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=timeout)
    if tail is not None:
        print(result.stderr[-tail:])
    elif result.returncode != 0:
        print(result.stderr[-4000:])
    check(result.returncode == 0, f"{label}fsi-run exits 0 (got {result.returncode})")
    record = manifest(run_dir)
    check(record["status"] == "completed", f"{label}run.json says completed")
    checks = record["checks"]
    check(checks["particles_final"] == checks["particles_initial"], f"{label}no particle lost")
    return record


def refused_client(scene, output, capabilities, overrides=()):
    """Opens a session with `scene`'s fsi-server (with `overrides`, KEY=EXPR) from a fake client
    offering only `capabilities` (session bits, e.g. 4: a client of protocol 1.2), checks that the server sends no set-up data,
    exits non-zero and records a failed run in `output`, and returns what the fake client printed
    (the server's Error text among it) for the test's own checks."""
    server, port = start_server(scene, output, overrides)
    fake = subprocess.run([binary("fake_peer"), "client-capabilities", "127.0.0.1", str(port), str(capabilities)],
                          capture_output=True, text=True, timeout=60, env=ENV)
    status = wait(server, 30)
    if status is None:
        kill_group(server)
        fail(f"fsi-server still runs after refusing a client of session capabilities {capabilities}")
    print(fake.stdout)
    check("received Setup" not in fake.stdout, "no set-up data before the refusal")
    check(status != 0 and manifest(output)["status"] == "failed",
          f"the server exits non-zero ({status}), run.json says failed")
    return fake.stdout


def cleanup(path):
    if os.environ.get("FSI_KEEP_TEST_OUTPUT"):
        print(f"kept {path}")
    else:
        shutil.rmtree(path, ignore_errors=True)


def boundary_checks(run, min_approach=0.3):
    """What every case with moving or flexible walls checks of its run.json (issue 14): no physics
    warning, action = reaction on the boundary to round-off, and no particle closer to a wall
    than `min_approach` r0 (none crossed one)."""
    check(run.get("warnings", []) == [], f"no physics warning: {run.get('warnings')}")
    checks = run["checks"]
    check(checks["max_action_reaction_relative"] < 1e-12,
          f"action = reaction on the boundary: {checks['max_action_reaction_relative']:.2e}")
    check(checks["closest_approach_over_r0"] > min_approach,
          f"no particle comes closer to a wall than {min_approach:g} r0: {checks['closest_approach_over_r0']:.3f}")
