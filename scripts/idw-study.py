#!/usr/bin/python3
"""Parameter study of the IDW rotation form (optimal-parameters paper: rotation, translation and
combined experiments).

Makes three planar meshes with gmsh (NACA 0012, a 1 x 0.2 rectangle, a unit square, each in
a circular far field of radius 10 with cells growing away from the body), then for every
exponent pair (st, sr) moves the body step by step, each step deforming the previous mesh,
until a cell inverts (deform_idw_study, a C++ program built with the tests). --motion picks
the experiment:

  rotation     (default) clockwise 5 degrees per step about the centre (quarter chord for the
               airfoil), all three shapes, up to 360 degrees. Writes OUT/idw-study.csv/.png.
  translation  upwards (+y, across the chord) 0.1 body lengths per step, all three shapes,
               up to 9.5 lengths. Writes OUT/idw-study-translation.csv/.png.
  combined     the paper's combined movements on the rectangle: 2 degrees clockwise about the
               moving centre plus 1 unit (case a) or 5 units (case b) upwards per step, one
               unit being --unit body lengths (0.05 by default; the paper gives no body size).
               Writes OUT/idw-study-combined.csv/.png.

CSV columns: shape,motion,st,sr,steps,max_angle,max_displacement,min_quality,mean_quality
(after the last valid step), reference_min_quality,reference_mean_quality (at 45 degrees,
2 lengths, or 20 degrees), failure_distance (from the body centre to the worst cell of the
first failed mesh). The PNG shows per shape / case the reach over (st, sr) and the min / mean
quality at the reference step against sr at st = 1 and against st at sr = 2 (translation:
sr = inf), plus where the mesh failed.

Usage: scripts/idw-study.py --program BUILD/tests/deform_idw_study --out DIR
       [--motion rotation|translation|combined] [--quick] [--require-angle DEGREES]
       [--check-rotation-term] [--check-translation-exponent]
--quick runs the square only on a small grid (used by the regression tests);
--require-angle fails (exit 1) when no exponent pair reaches that angle;
--check-rotation-term fails unless, at every st, sr = 2 reaches at least the angle of
sr = inf (no rotation term) with a better minimum quality at 45 degrees (the paper's finding
for rotation);
--check-translation-exponent (translation) fails unless sr changes nothing (same steps and
qualities for every sr) and st = 1 translates strictly further than every other st in the
grid (the paper's st optimum for translation).
"""
import argparse
import csv
import io
import math
import pathlib
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402

FARFIELD_RADIUS = 10.0
BODY_SIZE = 0.02
FARFIELD_SIZE = 1.0
FULL_ST = [0.5, 1.0, 1.5, 2.0, 3.0, 4.0]
FULL_SR = ["1", "2", "3", "4", "6", "inf"]
TRANSLATION_ST = [0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0, 4.0]
COMBINED_SR = ["1", "2", "4", "8", "inf"]
TRANSLATION_STEP = 0.1   # body lengths per step
PAPER_UNIT = 0.05        # body lengths per "unit length" of the paper's combined movements
COLUMNS = ["shape", "motion", "st", "sr", "steps", "max_angle", "max_displacement", "min_quality",
           "mean_quality", "reference_min_quality", "reference_mean_quality", "failure_distance"]


def naca0012(count=80):
    """Closed-trailing-edge NACA 0012, chord 1, counter-clockwise from the trailing edge."""
    def thickness(x):
        return 0.6 * (0.2969 * math.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1036 * x**4)
    xs = [0.5 * (1.0 - math.cos(math.pi * k / count)) for k in range(count + 1)]  # 0 .. 1
    upper = [(x, thickness(x)) for x in reversed(xs)]          # TE → LE over the top
    lower = [(x, -thickness(x)) for x in xs[1:-1]]             # LE → TE underneath
    return upper + lower


def rectangle(width, height, per_unit=50):
    corners = [(-width / 2, -height / 2), (width / 2, -height / 2), (width / 2, height / 2), (-width / 2, height / 2)]
    points = []
    for k in range(4):
        (x0, y0), (x1, y1) = corners[k], corners[(k + 1) % 4]
        n = max(2, round(math.hypot(x1 - x0, y1 - y0) * per_unit))
        points += [(x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * i / n) for i in range(n)]
    return points


SHAPES = {
    "naca0012": (naca0012, (0.25, 0.0)),
    "rectangle": (lambda: rectangle(1.0, 0.2), (0.0, 0.0)),
    "square": (lambda: rectangle(1.0, 1.0), (0.0, 0.0)),
}


def write_geo(path, body, centre):
    lines = [f"Point({i + 1}) = {{{x!r}, {y!r}, 0, {BODY_SIZE}}};" for i, (x, y) in enumerate(body)]
    n = len(body)
    lines += [f"Line({i + 1}) = {{{i + 1}, {(i + 1) % n + 1}}};" for i in range(n)]
    cx, cy = centre
    lines += [
        f"Point({n + 1}) = {{{cx}, {cy}, 0, {FARFIELD_SIZE}}};",
        f"Point({n + 2}) = {{{cx + FARFIELD_RADIUS}, {cy}, 0, {FARFIELD_SIZE}}};",
        f"Point({n + 3}) = {{{cx - FARFIELD_RADIUS}, {cy}, 0, {FARFIELD_SIZE}}};",
        f"Circle({n + 1}) = {{{n + 2}, {n + 1}, {n + 3}}};",
        f"Circle({n + 2}) = {{{n + 3}, {n + 1}, {n + 2}}};",
        f"Curve Loop(1) = {{{', '.join(str(i + 1) for i in range(n))}}};",
        f"Curve Loop(2) = {{{n + 1}, {n + 2}}};",
        "Plane Surface(1) = {2, 1};",
        f"Physical Curve(\"body\") = {{{', '.join(str(i + 1) for i in range(n))}}};",
        f"Physical Curve(\"farfield\") = {{{n + 1}, {n + 2}}};",
        "Physical Surface(\"fluid\") = {1};",
    ]
    path.write_text("\n".join(lines) + "\n")


def make_mesh(name, out):
    """gmsh → .msh → the plain text planar mesh deform_idw_study reads."""
    make_body, centre = SHAPES[name]
    geo, msh, text = out / f"{name}.geo", out / f"{name}.msh", out / f"{name}.mesh.txt"
    write_geo(geo, make_body(), centre)
    subprocess.run(["gmsh", "-2", "-format", "msh22", "-v", "1", str(geo), "-o", str(msh)], check=True)
    mesh = meshio.read(msh)
    names = {tag[0]: key for key, tag in mesh.field_data.items()}
    triangles = mesh.cells_dict["triangle"]
    edges = mesh.cells_dict["line"]
    edge_tags = mesh.cell_data_dict["gmsh:physical"]["line"]
    points = mesh.points[:, :2]
    used = sorted(set(triangles.flatten()))
    renumber = {old: new for new, old in enumerate(used)}
    with text.open("w") as stream:
        stream.write(f"points {len(used)}\n")
        for old in used:
            stream.write(f"{points[old][0]!r} {points[old][1]!r}\n")
        stream.write(f"triangles {len(triangles)}\n")
        for a, b, c in triangles:
            (ax, ay), (bx, by), (cx, cy) = points[a], points[b], points[c]
            if (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) < 0:  # counter-clockwise
                b, c = c, b
            stream.write(f"{renumber[a]} {renumber[b]} {renumber[c]}\n")
        stream.write("quads 0\n")
        stream.write(f"edges {len(edges)}\n")
        for (a, b), tag in zip(edges, edge_tags):
            stream.write(f"{renumber[a]} {renumber[b]} {0 if names[tag] == 'body' else 1}\n")
    return text, centre, len(used), len(triangles)


class Experiment:
    """One motion on one shape: the deform_idw_study options and how to label the results."""

    def __init__(self, shape, motion, label, options, reference, reach, reach_unit):
        self.shape, self.motion, self.label = shape, motion, label
        self.options, self.reference = options, reference  # reference: (step, description)
        self.reach, self.reach_unit = reach, reach_unit    # CSV column measuring how far it went


def experiments(motion, quick, unit):
    shapes = ["square"] if quick else list(SHAPES)
    if motion == "rotation":
        steps = 9 if quick else 72
        return [Experiment(shape, "rotation", shape,
                           ["--motion", "rotation", "--step-degrees", "5", "--max-steps", str(steps)],
                           (9, "45 deg"), "max_angle", "deg") for shape in shapes]
    if motion == "translation":
        # The far field is 10 lengths away; 9.5 lengths is as far as the body can go.
        steps = round((FARFIELD_RADIUS - 0.5) / TRANSLATION_STEP)
        return [Experiment(shape, "translation", shape,
                           ["--motion", "translation", "--step-length", str(TRANSLATION_STEP),
                            "--direction", "0,1", "--max-steps", str(steps)],
                           (20, f"{20 * TRANSLATION_STEP:g} lengths"), "max_displacement", "lengths")
                for shape in shapes]
    cases = [("a", 1)] if quick else [("a", 1), ("b", 5)]
    return [Experiment("rectangle", f"combined-{case}", f"rectangle ({case}): 2 deg + {units} unit/step",
                       ["--motion", "combined", "--step-degrees", "2", "--step-length", repr(units * unit),
                        "--direction", "0,1", "--max-steps", "180"],
                       (10, "20 deg"), "max_angle", "deg") for case, units in cases]


def run_study(program, mesh_text, centre, experiment, st_values, sr_values):
    result = subprocess.run(
        [str(program), str(mesh_text), "--centre", f"{centre[0]!r},{centre[1]!r}", *experiment.options,
         "--reference-step", str(experiment.reference[0]),
         "--st", ",".join(str(v) for v in st_values), "--sr", ",".join(sr_values)],
        capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"idw-study: error: {program} failed on {mesh_text}: {result.stderr.strip()}")
    return list(csv.DictReader(io.StringIO(result.stdout)))


def sr_key(label):
    return math.inf if label == "inf" else float(label)


def plot(rows, runs, path):
    figure, axes = plt.subplots(len(runs), 4, figsize=(20, 4.2 * len(runs)), squeeze=False)
    for row_axes, run in zip(axes, runs):
        data = [r for r in rows if r["_label"] == run.label]
        st_values = sorted({float(r["st"]) for r in data})
        sr_labels = sorted({r["sr"] for r in data}, key=sr_key)
        grid = [[next(float(r[run.reach]) for r in data if float(r["st"]) == st and r["sr"] == sr)
                 for sr in sr_labels] for st in st_values]
        image = row_axes[0].imshow(grid, origin="lower", cmap="viridis", aspect="auto")
        row_axes[0].set_xticks(range(len(sr_labels)), [s if s == "inf" else f"{float(s):g}" for s in sr_labels])
        row_axes[0].set_yticks(range(len(st_values)), [f"{v:g}" for v in st_values])
        row_axes[0].set_xlabel("sr")
        row_axes[0].set_ylabel("st")
        row_axes[0].set_title(f"{run.label}: reach ({run.reach_unit})", fontsize=9)
        for i, line in enumerate(grid):
            for j, value in enumerate(line):
                row_axes[0].text(j, i, f"{value:g}", ha="center", va="center", color="w", fontsize=8)
        figure.colorbar(image, ax=row_axes[0])
        fixed_sr = "inf" if run.motion == "translation" else "2"
        for axis, fixed_name, fixed_value, free_name in ((row_axes[1], "st", 1.0, "sr"),
                                                         (row_axes[2], "sr", fixed_sr, "st")):
            if fixed_name == "st":
                subset = [r for r in data if float(r["st"]) == fixed_value]
            else:
                subset = [r for r in data if r["sr"] == fixed_value]
            positions = range(len(subset))
            axis.plot(positions, [float(r["reference_min_quality"]) for r in subset], "o-", label="min quality")
            axis.plot(positions, [float(r["reference_mean_quality"]) for r in subset], "s-", label="mean quality")
            axis.set_xticks(list(positions), [r[free_name] for r in subset])
            axis.set_xlabel(free_name)
            axis.set_title(f"quality at {run.reference[1]} ({fixed_name} = {fixed_value})", fontsize=9)
            axis.set_ylim(0, 1)
            axis.legend()
        subset = [r for r in data if r["sr"] == fixed_sr]
        row_axes[3].plot([float(r["st"]) for r in subset], [float(r["failure_distance"]) for r in subset], "o-")
        row_axes[3].axhline(FARFIELD_RADIUS, color="grey", linestyle="--", label="far field")
        row_axes[3].set_xlabel("st")
        row_axes[3].set_ylabel("distance from body centre")
        row_axes[3].set_title(f"where the first cell inverts (sr = {fixed_sr})", fontsize=9)
        row_axes[3].legend()
    figure.tight_layout()
    figure.savefig(path, dpi=100)


def check_rotation_term(rows, st_values):
    for shape in sorted({r["shape"] for r in rows}):
        for st in st_values:
            pair = {r["sr"]: r for r in rows if r["shape"] == shape and float(r["st"]) == st}
            with_term, without = pair["2"], pair["inf"]
            # nan (failed before 45 degrees) compares false and so fails the check.
            if not (float(with_term["max_angle"]) >= float(without["max_angle"])
                    and float(with_term["reference_min_quality"]) > float(without["reference_min_quality"])):
                print(f"idw-study: {shape} st={st:g}: sr=2 ({with_term['max_angle']} deg, min quality "
                      f"{with_term['reference_min_quality']}) does not beat sr=inf ({without['max_angle']} deg, "
                      f"{without['reference_min_quality']})", file=sys.stderr)
                return False
    return True


def check_translation_exponent(rows, st_values):
    """sr has no effect on a pure translation; st = 1 goes strictly furthest."""
    if 1.0 not in st_values or len(st_values) < 2:
        print("idw-study: --check-translation-exponent needs st = 1 and another st", file=sys.stderr)
        return False
    for shape in sorted({r["shape"] for r in rows}):
        data = [r for r in rows if r["shape"] == shape]
        for st in st_values:
            same_st = [r for r in data if float(r["st"]) == st]
            signatures = {(r["steps"], r["min_quality"], r["mean_quality"]) for r in same_st}
            if len(signatures) != 1:
                print(f"idw-study: {shape} st={st:g}: the translation result depends on sr: {sorted(signatures)}",
                      file=sys.stderr)
                return False
        reach = {float(r["st"]): float(r["max_displacement"]) for r in data}
        for st, value in reach.items():
            if st != 1.0 and not reach[1.0] > value:
                print(f"idw-study: {shape}: st=1 translates {reach[1.0]:g} lengths, not further than "
                      f"st={st:g} ({value:g})", file=sys.stderr)
                return False
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument("--program", required=True, type=pathlib.Path, help="the deform_idw_study executable")
    parser.add_argument("--out", required=True, type=pathlib.Path, help="output folder")
    parser.add_argument("--motion", choices=["rotation", "translation", "combined"], default="rotation")
    parser.add_argument("--unit", type=float, default=PAPER_UNIT,
                        help="combined motion: body lengths per unit length of the paper (default 0.05)")
    parser.add_argument("--quick", action="store_true", help="square (combined: case a) only, small grid")
    parser.add_argument("--require-angle", type=float, default=None,
                        help="exit 1 unless some (st, sr) reaches this angle")
    parser.add_argument("--check-rotation-term", action="store_true",
                        help="exit 1 unless sr = 2 beats sr = inf at every st (rotation; needs both in the grid)")
    parser.add_argument("--check-translation-exponent", action="store_true",
                        help="exit 1 unless sr has no effect and st = 1 goes furthest (translation)")
    arguments = parser.parse_args()
    if not arguments.program.is_file():
        sys.exit(f"idw-study: error: {arguments.program} is not a file (build deform_idw_study first)")
    if not arguments.unit > 0:
        sys.exit(f"idw-study: error: --unit {arguments.unit} is not positive")
    if arguments.check_rotation_term and arguments.motion != "rotation":
        sys.exit("idw-study: error: --check-rotation-term needs --motion rotation")
    if arguments.check_translation_exponent and arguments.motion != "translation":
        sys.exit("idw-study: error: --check-translation-exponent needs --motion translation")
    arguments.out.mkdir(parents=True, exist_ok=True)
    if arguments.quick:
        st_values = {"rotation": [1.0, 2.0], "translation": [0.5, 1.0, 4.0], "combined": [1.0]}[arguments.motion]
        sr_values = ["2", "inf"]
    else:
        st_values = TRANSLATION_ST if arguments.motion == "translation" else FULL_ST
        sr_values = {"rotation": FULL_SR, "translation": ["1", "2", "inf"],
                     "combined": COMBINED_SR}[arguments.motion]

    rows, meshes = [], {}
    runs = experiments(arguments.motion, arguments.quick, arguments.unit)
    for run in runs:
        if run.shape not in meshes:
            meshes[run.shape] = make_mesh(run.shape, arguments.out)
            print(f"{run.shape}: {meshes[run.shape][2]} nodes, {meshes[run.shape][3]} triangles", flush=True)
        text, centre, _, _ = meshes[run.shape]
        print(f"{run.label} ({run.motion})", flush=True)
        for row in run_study(arguments.program, text, centre, run, st_values, sr_values):
            rows.append({"shape": run.shape, "motion": run.motion, "_label": run.label, **row})
            print(f"  st={row['st']:>4} sr={row['sr']:>4}: {float(row[run.reach]):>5g} {run.reach_unit}; "
                  f"quality at {run.reference[1]} min {float(row['reference_min_quality']):.3f} "
                  f"mean {float(row['reference_mean_quality']):.3f}; fails at "
                  f"{float(row['failure_distance']):.2f} from the centre", flush=True)
    stem = "idw-study" if arguments.motion == "rotation" else f"idw-study-{arguments.motion}"
    table, picture = arguments.out / f"{stem}.csv", arguments.out / f"{stem}.png"
    with table.open("w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=COLUMNS, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, runs, picture)
    print(f"wrote {table} and {picture}")
    best = max(float(r["max_angle"]) for r in rows)
    if arguments.require_angle is not None and best < arguments.require_angle:
        print(f"idw-study: largest angle reached {best:g} < required {arguments.require_angle:g}", file=sys.stderr)
        return 1
    if arguments.check_rotation_term and not check_rotation_term(rows, st_values):
        return 1
    if arguments.check_translation_exponent and not check_translation_exponent(rows, st_values):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
