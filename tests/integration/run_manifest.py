"""One reader for run.json (format_version 9) of every run mode: checks that the manifest has the
one shape fsi-server writes for coupled and --mbd-only runs, and returns it as a dict."""
import json
import os

FORMAT_VERSION = 9

# Every key of the shape, with the keys of its objects; None marks a leaf.
SHAPE = {
    "format": None, "format_version": None, "mode": None, "started_utc": None,
    "program": {"name": None, "version": None, "git_revision": None, "command_line": None},
    "protocol": None, "client": None,
    "scene": {"file": None, "fnv1a64": None, "overrides": None},
    "parameters": None, "parameters_flat": None, "dimension": None,
    "model": {"gravity": None, "bodies": None, "constraints": None, "integrator": None},
    "fluid": None,
    "mesh": {"vertices": None, "dynamic_vertices": None, "refinement_resolution": None},
    "wavemakers": None,
    "time_step": None, "end_time": None, "steps": None, "snapshots": None,
    "timings_seconds": {name: None for name in (
        "total", "setup_and_equilibration", "client_setup", "client_equilibration", "coupled_phase",
        "stepping", "mbd", "liggghts", "contact_fix", "communication", "client_mpi_communication",
        "output")},
    "newton": {"steps": None, "iterations": None, "jacobian_evaluations": None, "factorisations": None,
               "substepped_steps": None},
    "checks": {name: None for name in (
        "max_action_reaction_relative", "closest_approach_over_r0", "particles_initial",
        "particles_final", "snapshots_checked", "max_density_deviation_at_snapshots",
        "max_particle_speed_at_snapshots", "speed_of_sound",
        "max_particle_speed_over_speed_of_sound_at_snapshots", "max_particle_pairs_at_snapshots",
        "closest_particle_pair_over_spacing_at_snapshots", "closest_particle_pair_place",
        "closest_particle_pair_time", "position_constraint_drift", "velocity_constraint_drift")},
    "release": None,
    "health": None,
    "energy_audit": None,
    "checkpoints": None, "resumes": None,
    "warnings": None, "status": None, "reason": None,
}
# Present in a coupled run, null in an --mbd-only run.
COUPLED_ONLY = ("protocol", "fluid", "health")


class ManifestError(Exception):
    pass


def _check_shape(value, shape, where):
    for key, inner in shape.items():
        if key not in value:
            raise ManifestError(f"{where}: no key '{key}'")
        if inner is not None:
            if not isinstance(value[key], dict):
                raise ManifestError(f"{where}.{key}: not an object")
            _check_shape(value[key], inner, f"{where}.{key}")


def read_run_manifest(run_dir):
    """run.json of RUN_DIR, checked against the one shape; raises ManifestError naming the key."""
    path = os.path.join(run_dir, "run.json")
    with open(path) as handle:
        manifest = json.load(handle)
    if manifest.get("format") != "fsi-run-manifest" or manifest.get("format_version") != FORMAT_VERSION:
        raise ManifestError(f"{path}: not an fsi-run-manifest of format_version {FORMAT_VERSION} "
                            f"({manifest.get('format')!r}, {manifest.get('format_version')!r})")
    _check_shape(manifest, SHAPE, path)
    if manifest["mode"] not in ("coupled", "mbd-only"):
        raise ManifestError(f"{path}: unknown mode {manifest['mode']!r}")
    for key in COUPLED_ONLY:
        if (manifest[key] is None) != (manifest["mode"] == "mbd-only"):
            raise ManifestError(f"{path}: '{key}' must be null exactly in an --mbd-only run")
    if len(manifest["model"]["gravity"]) != manifest["dimension"]:
        raise ManifestError(f"{path}: model.gravity has {len(manifest['model']['gravity'])} components "
                            f"in a {manifest['dimension']}D run")
    if not isinstance(manifest["model"]["bodies"], list):
        raise ManifestError(f"{path}: model.bodies is not a list")
    if not isinstance(manifest["wavemakers"], list):
        raise ManifestError(f"{path}: wavemakers is not a list")
    return manifest
