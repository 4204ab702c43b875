#!/usr/bin/env python3
"""Compare deformation methods on a pitching body through `mixmesh deform`.

For each method the body is turned about a centre in fixed angle steps, each angle one
run that deforms the original mesh (a non-incremental rigid motion), until the command
fails (cells stay inverted after repair) or the largest angle is reached. Prints a
markdown table: largest angle before failure, quality at the report angle (smallest
scaled Jacobian, invalid cells, largest wall-line angle change) and the time of the run
at the report angle (the method's own time as the command reports it, the process wall
clock and the process CPU time).

Usage:
  scripts/compare-deform-methods.py --program BUILD/bin/mixmesh [--mesh cases/naca0012/naca0012.msh]
      [--methods idw,idw-simple,ara] [--step 5] [--max-angle 180] [--report-angle 20] [--out DIR]
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

# For each compared method: the motion file's method, its options table, and a label.
METHODS = {
    "idw": ("idw", "", "IDW rotation form (eq. 2-4, automatic exponents)"),
    "idw-simple": ("idw", '[idw]\nform = "simple"\n', "IDW simple form (eq. 1, tree code)"),
    "ara": ("ara", "", "ARA (default options)"),
}

AFTER = re.compile(r"step 1: after:\s+min scaled Jacobian ([-0-9.eE+]+), wall-line angle max ([-0-9.eE+]+) deg "
                   r"mean ([-0-9.eE+]+) deg, invalid (\d+)")
CHANGE = re.compile(r"step 1: wall-line angle change: moving walls ([-0-9.eE+]+) deg")
METHOD_TIME = re.compile(r"step 1/1 \([a-z]+\): ([0-9.eE+-]+) s")


def motion_text(method, marker, centre, axis, angle):
    kind, table, _ = METHODS[method]
    return (f"method = \"{kind}\"\nsteps = 1\n\n{table}\n[[body]]\nname = \"{marker}\"\nmarkers = [\"{marker}\"]\nmotion = \"rigid\"\n"
            f"centre = [{centre[0]}, {centre[1]}, {centre[2]}]\naxis = [{axis[0]}, {axis[1]}, {axis[2]}]\n"
            f"angle = {angle}\n")


def run(program, mesh, method, angle, arguments, directory):
    """One deformation to `angle`; returns a dict of figures, or None when the command failed."""
    motion = os.path.join(directory, f"{method}_{angle:g}.toml")
    with open(motion, "w") as handle:
        handle.write(motion_text(method, arguments.marker, arguments.centre, arguments.axis, angle))
    output = os.path.join(directory, f"{method}_{angle:g}.vtu")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    process = subprocess.run([program, "deform", mesh, "--motion", motion, "-o", output],
                             capture_output=True, text=True, timeout=arguments.timeout)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    text = process.stdout + process.stderr
    if process.returncode != 0:
        lines = [line for line in text.splitlines() if "rror" in line or "invalid" in line.lower()]
        return None, (lines[-1] if lines else text.strip().splitlines()[-1] if text.strip() else "failed")
    quality = AFTER.search(text)
    change = CHANGE.search(text)
    method_time = METHOD_TIME.search(text)
    if not quality:
        raise RuntimeError(f"{method} at {angle} deg: no quality line in the output:\n{text}")
    return {
        "min_scaled_jacobian": float(quality.group(1)),
        "invalid": int(quality.group(4)),
        "wall_angle_change": float(change.group(1)) if change else float("nan"),
        "method_seconds": float(method_time.group(1)) if method_time else float("nan"),
        "wall_seconds": wall,
        "cpu_seconds": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
    }, None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--program", required=True, help="the mixmesh executable")
    parser.add_argument("--mesh", default=os.path.join(os.path.dirname(__file__), "..", "cases", "naca0012",
                                                       "naca0012.msh"))
    parser.add_argument("--marker", default="airfoil", help="the moving marker")
    parser.add_argument("--centre", type=float, nargs=3, default=[0.25, 0.0, 0.0])
    parser.add_argument("--axis", type=float, nargs=3, default=[0.0, 0.0, -1.0], help="nose up for flow along +x")
    parser.add_argument("--methods", default="idw,ara", help="comma-separated: " + ", ".join(METHODS))
    parser.add_argument("--step", type=float, default=5.0, help="angle step, degrees")
    parser.add_argument("--max-angle", type=float, default=180.0)
    parser.add_argument("--report-angle", type=float, default=20.0)
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds per run")
    parser.add_argument("--out", help="directory for motion files and meshes (default: a temporary one)")
    arguments = parser.parse_args()
    methods = [name.strip() for name in arguments.methods.split(",") if name.strip()]
    for name in methods:
        if name not in METHODS:
            sys.exit(f"compare-deform-methods: unknown method '{name}' (known: {', '.join(METHODS)})")
    if not os.path.isfile(arguments.mesh):
        sys.exit(f"compare-deform-methods: no mesh at {arguments.mesh}")
    if not (arguments.step > 0.0):
        sys.exit("compare-deform-methods: the step must be positive")

    directory = arguments.out or tempfile.mkdtemp(prefix="mixmesh-compare-")
    os.makedirs(directory, exist_ok=True)
    rows = []
    for name in methods:
        largest, failure, report = 0.0, "", None
        count = int(round(arguments.max_angle / arguments.step))
        for k in range(1, count + 1):
            angle = k * arguments.step
            figures, error = run(arguments.program, arguments.mesh, name, angle, arguments, directory)
            if figures is None:
                # The first clause of the error: what failed, not the list of cells.
                failure = f"fails at {angle:g}°: " + error.strip().split(";")[0].replace("mixmesh: error: ", "")
                break
            largest = angle
            if abs(angle - arguments.report_angle) < 1e-9:
                report = figures
            print(f"{name}: {angle:g} deg valid, min scaled Jacobian {figures['min_scaled_jacobian']:.4f}",
                  file=sys.stderr)
        rows.append((name, largest, failure or f"valid up to {arguments.max_angle:g}°", report))

    angle = f"{arguments.report_angle:g}°"
    print(f"| method | largest valid angle | min scaled Jacobian at {angle} | invalid cells at {angle} | "
          f"wall-line angle change at {angle} | method time at {angle} | run wall / CPU at {angle} |")
    print("|---|---|---|---|---|---|---|")
    for name, largest, failure, report in rows:
        if report:
            cells = (f"{report['min_scaled_jacobian']:.4f} | {report['invalid']} | {report['wall_angle_change']:.2f}° | "
                     f"{report['method_seconds']:.3f} s | {report['wall_seconds']:.2f} s / {report['cpu_seconds']:.2f} s")
        else:
            cells = "– | – | – | – | –"
        print(f"| {METHODS[name][2]} | {largest:g}° ({failure}) | {cells} |")
    print(f"\nmesh {os.path.relpath(arguments.mesh)}, marker {arguments.marker}, centre {arguments.centre}, "
          f"axis {arguments.axis}, steps of {arguments.step:g}° (each deforms the original mesh); outputs in {directory}")


if __name__ == "__main__":
    main()
