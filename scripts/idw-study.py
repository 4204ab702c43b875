#!/usr/bin/python3
"""Parameter study of the IDW rotation form (optimal-parameters paper, rotation experiment).

Makes three planar meshes with gmsh (NACA 0012, a 1 x 0.2 rectangle, a unit square, each in
a circular far field of radius 10 with cells growing away from the body), then for every
exponent pair (st, sr) rotates the body clockwise 5 degrees per step until a cell inverts
(deform_idw_study, a C++ program built with the tests). Writes

  OUT/idw-study.csv   shape,st,sr,max_angle,min_quality,mean_quality (at the largest angle),
                      reference_min_quality,reference_mean_quality (at 45 degrees)
  OUT/idw-study.png   largest angle reached over (st, sr) per shape, and the min / mean
                      quality at 45 degrees against sr at st = 1 and against st at sr = 2

Usage: scripts/idw-study.py --program BUILD/tests/deform_idw_study --out DIR [--quick]
       [--require-angle DEGREES]
--quick runs the square only on a small grid (used by the regression test);
--require-angle fails (exit 1) when no exponent pair reaches that angle;
--check-rotation-term fails unless, at every st, sr = 2 reaches at least the angle of
sr = inf (no rotation term) with a better minimum quality at 45 degrees (the paper's finding
for rotation).
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
REFERENCE_ANGLE = 45
FULL_ST = [0.5, 1.0, 1.5, 2.0, 3.0, 4.0]
FULL_SR = ["1", "2", "3", "4", "6", "inf"]


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


def run_study(program, mesh_text, centre, st_values, sr_values, max_angle):
    result = subprocess.run(
        [str(program), str(mesh_text), str(centre[0]), str(centre[1]), "5", str(max_angle),
         ",".join(str(v) for v in st_values), ",".join(sr_values), str(REFERENCE_ANGLE)],
        check=True, capture_output=True, text=True)
    return list(csv.DictReader(io.StringIO(result.stdout)))


def plot(rows, shapes, path):
    figure, axes = plt.subplots(len(shapes), 3, figsize=(15, 4.2 * len(shapes)), squeeze=False)
    for row_axes, shape in zip(axes, shapes):
        data = [r for r in rows if r["shape"] == shape]
        st_values = sorted({float(r["st"]) for r in data})
        sr_labels = sorted({r["sr"] for r in data}, key=lambda s: math.inf if s == "inf" else float(s))
        grid = [[next(float(r["max_angle"]) for r in data if float(r["st"]) == st and r["sr"] == sr)
                 for sr in sr_labels] for st in st_values]
        image = row_axes[0].imshow(grid, origin="lower", cmap="viridis", aspect="auto")
        row_axes[0].set_xticks(range(len(sr_labels)), [s if s == "inf" else f"{float(s):g}" for s in sr_labels])
        row_axes[0].set_yticks(range(len(st_values)), [f"{v:g}" for v in st_values])
        row_axes[0].set_xlabel("sr")
        row_axes[0].set_ylabel("st")
        row_axes[0].set_title(f"{shape}: largest rotation reached (deg)")
        for i, line in enumerate(grid):
            for j, value in enumerate(line):
                row_axes[0].text(j, i, f"{value:g}", ha="center", va="center", color="w", fontsize=8)
        figure.colorbar(image, ax=row_axes[0])
        for axis, fixed_name, fixed_value, free_name in ((row_axes[1], "st", 1.0, "sr"), (row_axes[2], "sr", "2", "st")):
            if fixed_name == "st":
                subset = [r for r in data if float(r["st"]) == fixed_value]
            else:
                subset = [r for r in data if r["sr"] == fixed_value]
            labels = [r[free_name] for r in subset]
            positions = range(len(subset))
            axis.plot(positions, [float(r["reference_min_quality"]) for r in subset], "o-", label="min quality")
            axis.plot(positions, [float(r["reference_mean_quality"]) for r in subset], "s-", label="mean quality")
            axis.set_xticks(list(positions), labels)
            axis.set_xlabel(free_name)
            axis.set_title(f"{shape}: quality at {REFERENCE_ANGLE} deg ({fixed_name} = {fixed_value})")
            axis.set_ylim(0, 1)
            axis.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--program", required=True, type=pathlib.Path, help="the deform_idw_study executable")
    parser.add_argument("--out", required=True, type=pathlib.Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="square only, small grid, up to 45 degrees")
    parser.add_argument("--require-angle", type=float, default=None,
                        help="exit 1 unless some (st, sr) reaches this angle")
    parser.add_argument("--check-rotation-term", action="store_true",
                        help="exit 1 unless sr = 2 beats sr = inf at every st (needs both in the grid)")
    arguments = parser.parse_args()
    if not arguments.program.is_file():
        sys.exit(f"idw-study: error: {arguments.program} is not a file (build deform_idw_study first)")
    arguments.out.mkdir(parents=True, exist_ok=True)
    shapes = ["square"] if arguments.quick else list(SHAPES)
    st_values = [1.0, 2.0] if arguments.quick else FULL_ST
    sr_values = ["2", "inf"] if arguments.quick else FULL_SR
    max_angle = 45 if arguments.quick else 360

    rows = []
    for shape in shapes:
        text, centre, nodes, cells = make_mesh(shape, arguments.out)
        print(f"{shape}: {nodes} nodes, {cells} triangles", flush=True)
        for row in run_study(arguments.program, text, centre, st_values, sr_values, max_angle):
            rows.append({"shape": shape, **row})
            print(f"  st={row['st']:>4} sr={row['sr']:>4}: {row['max_angle']:>5} deg; quality at "
                  f"{REFERENCE_ANGLE} deg min {float(row['reference_min_quality']):.3f} "
                  f"mean {float(row['reference_mean_quality']):.3f}", flush=True)
    table = arguments.out / "idw-study.csv"
    with table.open("w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=["shape", "st", "sr", "max_angle", "min_quality", "mean_quality",
                                                    "reference_min_quality", "reference_mean_quality"])
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, shapes, arguments.out / "idw-study.png")
    print(f"wrote {table} and {arguments.out / 'idw-study.png'}")
    best = max(float(r["max_angle"]) for r in rows)
    if arguments.require_angle is not None and best < arguments.require_angle:
        print(f"idw-study: largest angle reached {best:g} < required {arguments.require_angle:g}", file=sys.stderr)
        return 1
    if arguments.check_rotation_term:
        for shape in shapes:
            for st in st_values:
                pair = {r["sr"]: r for r in rows if r["shape"] == shape and float(r["st"]) == st}
                with_term, without = pair["2"], pair["inf"]
                # nan (failed before 45 degrees) compares false and so fails the check.
                if not (float(with_term["max_angle"]) >= float(without["max_angle"])
                        and float(with_term["reference_min_quality"]) > float(without["reference_min_quality"])):
                    print(f"idw-study: {shape} st={st:g}: sr=2 ({with_term['max_angle']} deg, min quality "
                          f"{with_term['reference_min_quality']}) does not beat sr=inf ({without['max_angle']} deg, "
                          f"{without['reference_min_quality']})", file=sys.stderr)
                    return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
