#!/usr/bin/python3
"""Builds the wing case: a straight NACA 0012 wing (chord 1, span 3) between two
planes, as the planar section mesh (wing_section.geo, meshed by gmsh) extruded
along z: hexahedra from the viscous-layer quads, prisms from the triangles.

Writes wing.msh (Gmsh 2.2; markers wing, farfield, root, tip) and
bend_twist_mode.csv, a bending + twist mode shape on the wing nodes
("x,y,z,dx,dy,dz": plunge 0.15 (z/span)^2, twist 6 deg (z/span) nose up about
the quarter chord).

    ./make_wing.py [--span-layers 12] [--span 3] [--wall-spacing 0.002] [--output wing.msh]
                   [--mode bend_twist_mode.csv]

The quasi-2D viscous case (one cell thick, first layer 1e-5 chords, no mode file):

    ./make_wing.py --span-layers 1 --span 0.05 --wall-spacing 1e-5 --output quasi2d.msh --mode ""
"""
import argparse
import math
import pathlib
import subprocess
import sys
import tempfile

import meshio
import numpy

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts"))
from msh22 import write_msh22  # noqa: E402


def section_mesh(folder, wall_spacing):
    with tempfile.TemporaryDirectory() as scratch:
        # The section's first layer height is the geo file's hwall_n, replaced here.
        text = (folder / "wing_section.geo").read_text()
        marker = "Field[1].hwall_n = "
        start = text.index(marker) + len(marker)
        text = text[:start] + repr(wall_spacing) + text[text.index(";", start):]
        source = pathlib.Path(scratch) / "section.geo"
        source.write_text(text)
        target = pathlib.Path(scratch) / "section.msh"
        subprocess.run(["gmsh", "-2", str(source), "-format", "msh22", "-o", str(target)],
                       check=True, capture_output=True)
        return meshio.read(target)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--span", type=float, default=3.0)
    parser.add_argument("--span-layers", type=int, default=12)
    parser.add_argument("--wall-spacing", type=float, default=0.002,
                        help="first layer height of the section (chords)")
    parser.add_argument("--output", default="wing.msh")
    parser.add_argument("--mode", default="bend_twist_mode.csv",
                        help="mode file to write; empty: none")
    arguments = parser.parse_args()
    folder = pathlib.Path(__file__).resolve().parent
    section = section_mesh(folder, arguments.wall_spacing)

    # Planar cells and the marked boundary lines of the section.
    # The section's curve "airfoil" becomes the volume mesh's marker "wing".
    names = {int(tag): "wing" if name == "airfoil" else name for name, (tag, _) in section.field_data.items()}
    triangles, quads, lines = [], [], []
    for block, tags in zip(section.cells, section.cell_data["gmsh:physical"]):
        if block.type == "triangle":
            triangles.append(block.data)
        elif block.type == "quad":
            quads.append(block.data)
        elif block.type == "line":
            lines += [(tuple(edge), names[int(tag)]) for edge, tag in zip(block.data, tags)]
    used = numpy.unique(numpy.concatenate([c.ravel() for c in triangles + quads]))
    renumber = -numpy.ones(len(section.points), dtype=int)
    renumber[used] = numpy.arange(len(used))
    xy = section.points[used, :2]
    triangles = renumber[numpy.concatenate(triangles)] if triangles else numpy.zeros((0, 3), int)
    quads = renumber[numpy.concatenate(quads)] if quads else numpy.zeros((0, 4), int)

    def counter_clockwise(cells):
        p = xy[cells]
        area = sum(p[:, k, 0] * p[:, (k + 1) % cells.shape[1], 1] - p[:, (k + 1) % cells.shape[1], 0] * p[:, k, 1]
                   for k in range(cells.shape[1]))
        cells = cells.copy()
        cells[area < 0] = cells[area < 0][:, ::-1]
        return cells

    triangles, quads = counter_clockwise(triangles), counter_clockwise(quads)
    count = len(xy)
    layers = arguments.span_layers
    z = numpy.linspace(0.0, arguments.span, layers + 1)
    points = numpy.vstack([numpy.column_stack([xy, numpy.full(count, level)]) for level in z])

    elements = []  # (gmsh type, physical name, nodes)
    for k in range(layers):
        low, high = k * count, (k + 1) * count
        elements += [(5, "fluid", list(q + low) + list(q + high)) for q in quads]
        elements += [(6, "fluid", list(t + low) + list(t + high)) for t in triangles]
    for name, level in (("root", 0), ("tip", layers)):
        offset = level * count
        flip = name == "root"  # outward: -z at the root, +z at the tip
        elements += [(3, name, list((q[::-1] if flip else q) + offset)) for q in quads]
        elements += [(2, name, list((t[::-1] if flip else t) + offset)) for t in triangles]
    for (a, b), name in lines:
        a, b = renumber[a], renumber[b]
        for k in range(layers):
            elements.append((3, name, [a + k * count, b + k * count, b + (k + 1) * count, a + (k + 1) * count]))

    physical = {"fluid": (3, 1), "root": (2, 2), "tip": (2, 3), "farfield": (2, 4), "wing": (2, 5)}
    output = folder / arguments.output
    write_msh22(output, points, elements, physical)

    # Bending + twist mode on the wing surface nodes.
    wing_nodes = []
    if arguments.mode:
        wing_nodes = sorted({n for kind, name, nodes in elements if name == "wing" for n in nodes})
        with open(folder / arguments.mode, "w") as stream:
            stream.write("x,y,z,dx,dy,dz\n")
            for node in wing_nodes:
                x, y, zz = points[node]
                fraction = zz / arguments.span
                twist = math.radians(6.0) * fraction
                dx = 0.25 + (x - 0.25) * math.cos(twist) + y * math.sin(twist) - x
                dy = -(x - 0.25) * math.sin(twist) + y * math.cos(twist) - y + 0.15 * fraction ** 2
                stream.write("%.17g,%.17g,%.17g,%.17g,%.17g,0\n" % (x, y, zz, dx, dy))
    print("%s: %d points, %d hexahedra, %d prisms; %d mode rows" %
          (output.name, len(points), layers * len(quads), layers * len(triangles), len(wing_nodes)))


if __name__ == "__main__":
    main()
