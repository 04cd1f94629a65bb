#!/usr/bin/python3
"""The finite-volume reference of the laminar flow around a cylinder (thesis §6.4, issue 14):
OpenFOAM's simpleFoam (Debian's `openfoam` package) on the same effective geometry as our SPH scene,
steady, at three mesh levels, and the velocity profile across the channel on the cylinder's
centre line written as this example's reference.

  openfoam_reference.py [--output out/cylinder_openfoam] [--levels 1,2,4] [--write reference.csv]
                        [--transient T0,T1] [--inlet 0.5] [--outlet 0.35] [--width 0.18] [--radius 0.014]

Geometry (Geometry block of cylinder_model.inc): a channel of width W = 0.18 m (walls at
x = +-W/2), a cylinder of radius r = 0.014 m at the origin, the inlet Lin = 0.5 m below it with a
uniform velocity v0 = 0.1 m/s along +y, the outlet Lout = 0.35 m above it at p = 0, no slip on the
walls and on the cylinder, nu = 1e-3 m^2/s (Re = 2 v0 r / nu = 2.8: steady, no separation).
The mesh: an O-grid of four blocks between the cylinder and the square |x|, |y| <= W/2 (graded
towards the cylinder), and a channel block below and above it; level k has 20 k cells along each
quarter of the cylinder and along the square's sides, 20 k radially, and cells of the same size
along the channel. SIMPLEC (consistent), second-order (linearUpwind) convection, converged to
residuals of 1e-8.

Each level runs in OUTPUT/level_<k> (blockMesh, then simpleFoam; skipped when its profile is
there). The profile u_y(x) on y = 0 is sampled at 181 points on each side of the cylinder (cellPoint
interpolation). Printed:
u_y at the SPH scene's 13 probe positions for every level, and the finest level's change from the
one before it (the mesh convergence). --write FILE writes the finest level's profile and the
others' as columns of a CSV (the example's reference.csv, with its provenance in comment lines).

The geometry options serve the studies of README.md and docs/validation.md: --inlet, the inlet's
distance below the cylinder, stands for the piston's (the SPH piston approaches from 0.8 m to 0.25 m
over the run); --width and --radius give the effective geometry of the SPH walls (W - 2d, r + d).
The probes stay at the scene's positions x = k 0.18/12 whatever the width.

OpenFOAM is not needed by the test suite: reference.csv is stored in the example."""
import argparse
import datetime
import math
import os
import subprocess
import sys

WIDTH = 0.18
RADIUS = 0.014
INLET = 0.5
OUTLET = 0.35
SPEED = 0.1
NU = 1e-3
THICKNESS = 0.001
SAMPLES = 181
TIME_STEP = 0.005     # pimpleFoam's step at level 1, divided by the level (Courant number about 0.3)
SAMPLE_EVERY = 0.05   # the transient profile's sampling interval [s]
PROBES = [k * 0.18 / 12 for k in range(-6, 7)]   # the scene's 13 probes, wall to wall (cylinder_model.inc)

HEADER = """FoamFile
{{
    version 2.0;
    format ascii;
    class {cls};
    object {name};
}}
"""


def foam_file(path, cls, name, body):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as handle:
        handle.write(HEADER.format(cls=cls, name=name) + body)


def block_mesh(level):
    """blockMeshDict of the O-grid around the cylinder and the two channel blocks."""
    a = WIDTH / 2
    c = RADIUS / math.sqrt(2.0)
    n = 20 * level                      # cells along a quarter and along a square side
    radial = 20 * level                 # cells from the square to the cylinder
    cell = WIDTH / n                    # the square side's cell size, kept along the channel
    n_in = max(1, round((INLET - a) / cell))
    n_out = max(1, round((OUTLET - a) / cell))
    plane = [(-c, -c), (c, -c), (c, c), (-c, c), (-a, -a), (a, -a), (a, a), (-a, a),
             (-a, -INLET), (a, -INLET), (a, OUTLET), (-a, OUTLET)]
    vertices = [f"    ({x:.9g} {y:.9g} {z:g})" for z in (0.0, THICKNESS) for x, y in plane]
    top = len(plane)

    def hexa(ids, cells, grading):
        return (f"    hex ({' '.join(str(i) for i in ids)} {' '.join(str(i + top) for i in ids)}) "
                f"({cells[0]} {cells[1]} 1) simpleGrading ({grading[0]} {grading[1]} 1)")
    towards_cylinder = 0.2              # last cell / first cell, square -> cylinder
    blocks = [hexa((4, 5, 1, 0), (n, radial), (1, towards_cylinder)),
              hexa((5, 6, 2, 1), (n, radial), (1, towards_cylinder)),
              hexa((6, 7, 3, 2), (n, radial), (1, towards_cylinder)),
              hexa((7, 4, 0, 3), (n, radial), (1, towards_cylinder)),
              hexa((8, 9, 5, 4), (n, n_in), (1, 1)),
              hexa((7, 6, 10, 11), (n, n_out), (1, 1))]
    arcs = []
    for z_offset in (0, top):
        for i, j, (x, y) in ((0, 1, (0, -RADIUS)), (1, 2, (RADIUS, 0)), (2, 3, (0, RADIUS)), (3, 0, (-RADIUS, 0))):
            z = THICKNESS if z_offset else 0.0
            arcs.append(f"    arc {i + z_offset} {j + z_offset} ({x:.9g} {y:.9g} {z:g})")

    def faces(pairs):
        return "\n".join(f"            ({i} {j} {j + top} {i + top})" for i, j in pairs)
    front_back = []
    for ids in ((4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3), (8, 9, 5, 4), (7, 6, 10, 11)):
        front_back.append(f"            ({ids[0]} {ids[3]} {ids[2]} {ids[1]})")
        front_back.append(f"            ({' '.join(str(i + top) for i in ids)})")
    body = f"""
convertToMeters 1;
vertices
(
{chr(10).join(vertices)}
);
blocks
(
{chr(10).join(blocks)}
);
edges
(
{chr(10).join(arcs)}
);
boundary
(
    inlet {{ type patch; faces ( {faces([(8, 9)]).strip()} ); }}
    outlet {{ type patch; faces ( {faces([(10, 11)]).strip()} ); }}
    walls
    {{
        type wall;
        faces
        (
{faces([(4, 8), (7, 4), (11, 7), (9, 5), (5, 6), (6, 10)])}
        );
    }}
    cylinder
    {{
        type wall;
        faces
        (
{faces([(1, 0), (2, 1), (3, 2), (0, 3)])}
        );
    }}
    frontAndBack
    {{
        type empty;
        faces
        (
{chr(10).join(front_back)}
        );
    }}
);
"""
    return body


def write_case(case, level, transient):
    """The case's dictionaries; transient = None (simpleFoam, steady) or (T0, T1) (pimpleFoam to T1)."""
    foam_file(os.path.join(case, "system", "blockMeshDict"), "dictionary", "blockMeshDict", block_mesh(level))
    if transient:
        # From rest, the inlet ramped like the scene's piston; the profile sampled every SAMPLE_EVERY s.
        control = f"""application pimpleFoam;
startFrom startTime;
startTime 0;
stopAt endTime;
endTime {transient[1]:g};
deltaT {TIME_STEP / level:g};
writeControl runTime;
writeInterval {transient[1]:g};
"""
        sampling = f"writeControl timeStep;\n        writeInterval {round(SAMPLE_EVERY * level / TIME_STEP)};"
    else:
        control = """application simpleFoam;
startFrom startTime;
startTime 0;
stopAt endTime;
endTime 20000;
deltaT 1;
writeControl timeStep;
writeInterval 20000;
"""
        sampling = "writeControl onEnd;"
    foam_file(os.path.join(case, "system", "controlDict"), "dictionary", "controlDict", f"""
{control}purgeWrite 1;
writeFormat ascii;
writePrecision 10;
runTimeModifiable false;
functions
{{
    profile
    {{
        type sets;
        libs ("libsampling.so");
        {sampling}
        interpolationScheme cellPoint;
        setFormat raw;
        fields (U);
        sets
        (
            left
            {{
                type uniform;
                axis x;
                start (-{WIDTH / 2:.9g} 0 {THICKNESS / 2:g});
                end (-{RADIUS:.9g} 0 {THICKNESS / 2:g});
                nPoints {SAMPLES};
            }}
            right
            {{
                type uniform;
                axis x;
                start ({RADIUS:.9g} 0 {THICKNESS / 2:g});
                end ({WIDTH / 2:.9g} 0 {THICKNESS / 2:g});
                nPoints {SAMPLES};
            }}
        );
    }}
}}
""")
    ddt = "backward" if transient else "steadyState"
    foam_file(os.path.join(case, "system", "fvSchemes"), "dictionary", "fvSchemes", f"\nddtSchemes {{ default {ddt}; }}" + """
gradSchemes { default Gauss linear; }
divSchemes
{
    default none;
    div(phi,U) bounded Gauss linearUpwind grad(U);
    div((nuEff*dev2(T(grad(U))))) Gauss linear;
}
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
""")
    if transient:
        solution = """
solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-9; relTol 0.01; }
    pFinal { $p; relTol 0; }
    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-10; relTol 0; }
    UFinal { $U; }
}
PIMPLE { nOuterCorrectors 1; nCorrectors 3; nNonOrthogonalCorrectors 1; }
"""
        # the scene's piston speed: v0 (1 - cos(pi t)) / 2 for t < 1 s, then v0 (cylinder_model.inc)
        ramp = " ".join(f"({t:g} (0 {SPEED * (1 - math.cos(math.pi * t)) / 2:.9g} 0))" for t in
                        (k / 50 for k in range(51)))
        inlet = f"type uniformFixedValue; uniformValue table ({ramp} (1000 (0 {SPEED:g} 0)));"
    else:
        solution = """
solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-10; relTol 0.05; }
    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-12; relTol 0.1; }
}
SIMPLE
{
    nNonOrthogonalCorrectors 1;
    consistent yes;
    residualControl { p 1e-8; U 1e-8; }
}
relaxationFactors { equations { U 0.9; } }
"""
        inlet = f"type fixedValue; value uniform (0 {SPEED:g} 0);"
    foam_file(os.path.join(case, "system", "fvSolution"), "dictionary", "fvSolution", solution)
    foam_file(os.path.join(case, "constant", "transportProperties"), "dictionary", "transportProperties",
              f"\ntransportModel Newtonian;\nnu {NU:g};\n")
    foam_file(os.path.join(case, "constant", "turbulenceProperties"), "dictionary", "turbulenceProperties",
              "\nsimulationType laminar;\n")
    foam_file(os.path.join(case, "0", "U"), "volVectorField", "U", f"""
dimensions [0 1 -1 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{{
    inlet {{ {inlet} }}
    outlet {{ type zeroGradient; }}
    walls {{ type noSlip; }}
    cylinder {{ type noSlip; }}
    frontAndBack {{ type empty; }}
}}
""")
    foam_file(os.path.join(case, "0", "p"), "volScalarField", "p", """
dimensions [0 2 -2 0 0 0 0];
internalField uniform 0;
boundaryField
{
    inlet { type zeroGradient; }
    outlet { type fixedValue; value uniform 0; }
    walls { type zeroGradient; }
    cylinder { type zeroGradient; }
    frontAndBack { type empty; }
}
""")


def profile_folders(case):
    """[(time, folder)] of the sampled profiles (left_U.xy, right_U.xy) of a case, in time order."""
    root = os.path.join(case, "postProcessing", "profile")
    found = []
    for name in os.listdir(root) if os.path.isdir(root) else []:
        path = os.path.join(root, name)
        try:
            time = float(name)
        except ValueError:
            continue
        if all(os.path.isfile(os.path.join(path, f"{side}_U.xy")) for side in ("left", "right")):
            found.append((time, path))
    return sorted(found)


def finished(case, transient):
    folders = profile_folders(case)
    return bool(folders) and (not transient or folders[-1][0] >= transient[1] - 1e-9)


def run_case(case, level, environment, transient):
    if finished(case, transient):
        print(f"{case}: done before, not run again", flush=True)
        return
    write_case(case, level, transient)
    solver = "pimpleFoam" if transient else "simpleFoam"
    for command in (["blockMesh"], ["checkMesh"], [solver]):
        log = os.path.join(case, f"log.{command[0]}")
        with open(log, "w") as handle:
            status = subprocess.run(command + ["-case", case], stdout=handle, stderr=subprocess.STDOUT,
                                    env=environment).returncode
        if status != 0:
            sys.exit(f"openfoam_reference.py: {command[0]} failed in {case} (exit {status}); see {log}")
    if not finished(case, transient):
        sys.exit(f"openfoam_reference.py: {solver} wrote no (complete) profile in {case}; see {case}/log.{solver}")


def case_profile(case, transient, window=None):
    """(x, u_y): the steady case's last profile, or the transient case's profile averaged over the
    window (default: the --transient window), every sample weighted alike (they are equidistant)."""
    folders = profile_folders(case)
    if not transient:
        return read_profile(folders[-1][1])
    t0, t1 = window or transient
    chosen = [path for time, path in folders if t0 - 1e-9 <= time <= t1 + 1e-9]
    if not chosen:
        sys.exit(f"openfoam_reference.py: no profile sampled in {t0:g}-{t1:g} s in {case} (one every "
                 f"{SAMPLE_EVERY:g} s); give a window of at least {SAMPLE_EVERY:g} s")
    profiles = [read_profile(path) for path in chosen]
    xs = profiles[0][0]
    return xs, [sum(p[1][i] for p in profiles) / len(profiles) for i in range(len(xs))]


def read_profile(folder):
    """(x, u_y) of the left and right raw sets files (columns x ux uy uz), joined in x."""
    xs, uys = [], []
    for side in ("left", "right"):
        with open(os.path.join(folder, f"{side}_U.xy")) as handle:
            for line in handle:
                parts = line.split()
                if len(parts) >= 4 and not line.startswith("#"):
                    xs.append(float(parts[0]))
                    uys.append(float(parts[2]))
    return xs, uys


def interpolate(xs, values, x):
    """values at x, linear between the samples around it; None where no two samples bracket x
    (inside the cylinder, on a wall)."""
    for i in range(1, len(xs)):
        if xs[i - 1] <= x <= xs[i] and xs[i] - xs[i - 1] < 2.5 * (WIDTH / 2 - RADIUS) / (SAMPLES - 1):
            w = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return (1 - w) * values[i - 1] + w * values[i]
    return None


def shown(value):
    return f"{value:9.5f}" if value is not None else "        -"


def iterations(case, solver):
    count = 0
    with open(os.path.join(case, f"log.{solver}")) as handle:
        for line in handle:
            if line.startswith("Time = "):
                count += 1
    return count


def window_pair(text, option):
    try:
        t0, t1 = (float(v) for v in text.split(","))
    except ValueError:
        sys.exit(f"openfoam_reference.py: {option} {text!r}: give two times T0,T1 in seconds, e.g. 2,6")
    if not 0 <= t0 < t1:
        sys.exit(f"openfoam_reference.py: {option} {text!r}: needs 0 <= T0 < T1")
    return t0, t1


def main():
    global INLET, OUTLET, WIDTH, RADIUS
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--output", default=os.path.join("out", "cylinder_openfoam"))
    parser.add_argument("--levels", default="1,2,4", help="mesh levels k (20 k cells per quarter), ascending")
    parser.add_argument("--write", help="write the profiles as this CSV (the example's reference.csv)")
    parser.add_argument("--transient", metavar="T0,T1",
                        help="pimpleFoam from rest with the piston's ramp to T1, the profile averaged over T0-T1 "
                             "(the SPH run's window, e.g. 2,6); default: simpleFoam, steady")
    parser.add_argument("--inlet", type=float, default=INLET, help=f"inlet distance below the cylinder [m] (default {INLET})")
    parser.add_argument("--outlet", type=float, default=OUTLET, help=f"outlet height above the cylinder [m] (default {OUTLET})")
    parser.add_argument("--width", type=float, default=WIDTH, help=f"channel width [m] (default {WIDTH})")
    parser.add_argument("--radius", type=float, default=RADIUS, help=f"cylinder radius [m] (default {RADIUS})")
    args = parser.parse_args()
    if not 0 < args.radius < args.width / 2 < min(args.inlet, args.outlet):
        parser.error(f"geometry radius {args.radius} < width/2 {args.width / 2} < inlet {args.inlet} and outlet "
                     f"{args.outlet} does not hold: the O-grid square |x|, |y| <= width/2 must fit between them")
    INLET, OUTLET, WIDTH, RADIUS = args.inlet, args.outlet, args.width, args.radius
    try:
        levels = sorted(int(v) for v in args.levels.split(","))
    except ValueError:
        parser.error(f"--levels {args.levels!r}: give whole numbers separated by commas, e.g. 1,2,4")
    foam_dir = os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam")
    if not os.path.isfile(os.path.join(foam_dir, "etc", "controlDict")):
        sys.exit(f"openfoam_reference.py: no OpenFOAM installation at {foam_dir}; apt-get install openfoam "
                 "(Debian 12), or set WM_PROJECT_DIR to yours")
    environment = dict(os.environ, WM_PROJECT_DIR=foam_dir)
    transient = window_pair(args.transient, "--transient") if args.transient else None
    solver = "pimpleFoam" if transient else "simpleFoam"
    profiles = {}
    for level in levels:
        case = os.path.join(args.output, f"{'transient_' if transient else ''}level_{level}")
        run_case(case, level, environment, transient)
        profiles[level] = case_profile(case, transient)
        print(f"level {level}: {iterations(case, solver)} {'time steps' if transient else 'SIMPLE iterations'}",
              flush=True)
    if transient and transient[1] - transient[0] >= 2:
        # the finest level's mean over each second of the window: how far the flow is from steady
        case = os.path.join(args.output, f"transient_level_{levels[-1]}")
        seconds = [(t, t + 1) for t in range(math.ceil(transient[0]), math.floor(transient[1]))]
        parts = {w: case_profile(case, transient, w) for w in seconds}
        print(f"level {levels[-1]}, mean over each second:")
        print("x [m]     " + "  ".join(f"{a:g}-{b:g} s   " for a, b in seconds))
        for x in PROBES:
            print(f"{x:+.4f}  " + "  ".join(shown(interpolate(*parts[w], x)) for w in seconds))
    print("x [m]     " + "  ".join(f"level {k:<3d}" for k in levels))
    for x in PROBES:
        print(f"{x:+.4f}  " + "  ".join(shown(interpolate(*profiles[k], x)) for k in levels))
    if len(levels) >= 2:
        fine, coarse = levels[-1], levels[-2]
        pairs = [(interpolate(*profiles[fine], x), interpolate(*profiles[coarse], x)) for x in PROBES]
        change = max(abs(a - b) for a, b in pairs if a is not None and b is not None)
        peak = max(abs(v) for v in profiles[fine][1])
        print(f"mesh convergence: level {fine} differs from level {coarse} by at most {change:.2e} m/s at the probes, "
              f"{100 * change / peak:.3f} % of the peak {peak:.5f} m/s")
    if args.write:
        xs = profiles[levels[-1]][0]
        with open(args.write, "w") as handle:
            how = (f"pimpleFoam from rest, inlet ramped like the piston, u_y averaged over {transient[0]:g}-{transient[1]:g} s "
                   f"(--transient {args.transient})" if transient else "simpleFoam (steady)")
            handle.write(f"# OpenFOAM reference of examples/cylinder (thesis §6.4): {how}; written by "
                         f"openfoam_reference.py --levels {args.levels} on {datetime.date.today()}\n")
            handle.write(f"# channel W = {WIDTH} m, cylinder r = {RADIUS} m, inlet {INLET} m below at v0 = {SPEED} m/s, "
                         f"outlet {OUTLET} m above at p = 0, nu = {NU} m^2/s; u_y on y = 0, cellPoint samples\n")
            handle.write("x," + ",".join(f"uy_level_{k}" for k in levels) + "\n")
            for x in xs:
                values = [interpolate(*profiles[k], x) for k in levels]
                if all(v is not None for v in values):
                    handle.write(f"{x:.6f}," + ",".join(f"{v:.7f}" for v in values) + "\n")
        print(f"reference: {args.write}")


if __name__ == "__main__":
    main()
