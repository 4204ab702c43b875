#!/usr/bin/env python3
"""Picture of a planar cut through a volume mesh, each cut cell filled by its type.

    plot-mesh-cut.py MESH --axis y --position 0.5 -o cut.png
        [--window HMIN HMAX VMIN VMAX] [--zoom HMIN HMAX VMIN VMAX] [--title TEXT]
        [--size 1600x1000]

Every cell that crosses the plane axis = position is intersected with it exactly (the
polygon through the points where its edges cross the plane) and filled with the colour
of its type: hexahedra blue, prisms green, tetrahedra red, pyramids yellow, as in Wild's
figures of the smooth mixed meshes. The window is in the plane's own coordinates (for
a y cut: x horizontal, z vertical); cells outside it are skipped, which keeps large
meshes fast. --zoom adds a second panel with a close-up (e.g. of the boundary layer
at the leading edge). Reads any format meshio reads (VTU, Gmsh, SU2, CGNS). Headless (Agg).
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.patches import Patch, Rectangle  # noqa: E402

# meshio cell type -> (label, RGB fill); the regression check reads these.
CELL_COLOURS = {
    "hexahedron": ("hexahedra", (0.16, 0.38, 0.85)),
    "wedge": ("prisms", (0.18, 0.68, 0.24)),
    "tetra": ("tetrahedra", (0.86, 0.18, 0.18)),
    "pyramid": ("pyramids", (0.98, 0.80, 0.08)),
}

# Edges of each cell type in VTK/meshio node order.
CELL_EDGES = {
    "tetra": [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)],
    "pyramid": [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 4), (2, 4), (3, 4)],
    "wedge": [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)],
    "hexahedron": [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
                   (0, 4), (1, 5), (2, 6), (3, 7)],
}

AXES = {"x": (0, (1, 2)), "y": (1, (0, 2)), "z": (2, (0, 1))}
AXIS_NAMES = "xyz"


def cut_polygons(points, cells, cell_type, axis, position, window):
    """Polygons (in-plane coordinates) where the cells cross the plane."""
    normal_axis, (first, second) = AXES[axis]
    coordinate = points[:, normal_axis][cells]
    crossing = (coordinate.min(axis=1) < position) & (coordinate.max(axis=1) >= position)
    if window is not None:
        horizontal = points[:, first][cells]
        vertical = points[:, second][cells]
        crossing &= (horizontal.max(axis=1) >= window[0]) & (horizontal.min(axis=1) <= window[1])
        crossing &= (vertical.max(axis=1) >= window[2]) & (vertical.min(axis=1) <= window[3])
    cells = cells[crossing]
    if len(cells) == 0:
        return []
    edges = np.array(CELL_EDGES[cell_type])
    start = points[cells[:, edges[:, 0]]]  # cells x edges x 3
    end = points[cells[:, edges[:, 1]]]
    below_start = start[:, :, normal_axis] < position
    below_end = end[:, :, normal_axis] < position
    cut = below_start != below_end
    denominator = end[:, :, normal_axis] - start[:, :, normal_axis]
    denominator[~cut] = 1.0
    t = (position - start[:, :, normal_axis]) / denominator
    crossing_points = start + t[:, :, None] * (end - start)
    in_plane = crossing_points[:, :, [first, second]]
    polygons = []
    for cell in range(len(cells)):
        corners = in_plane[cell][cut[cell]]
        if len(corners) < 3:
            continue
        centre = corners.mean(axis=0)
        angles = np.arctan2(corners[:, 1] - centre[1], corners[:, 0] - centre[0])
        polygons.append(corners[np.argsort(angles)])
    return polygons


def parse_size(text):
    try:
        width, height = (int(value) for value in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size '{text}' is not WIDTHxHEIGHT in pixels")
    if width < 100 or height < 100:
        raise argparse.ArgumentTypeError(f"size '{text}' is below 100x100 pixels")
    return width, height


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh", help="volume mesh (VTU, MSH, SU2, CGNS)")
    parser.add_argument("--axis", choices="xyz", default="y", help="normal of the cut plane (default y)")
    parser.add_argument("--position", type=float, default=None,
                        help="plane position along the axis (default: the middle of the mesh)")
    parser.add_argument("--window", type=float, nargs=4, metavar=("HMIN", "HMAX", "VMIN", "VMAX"),
                        help="picture window in the plane's coordinates (default: the whole cut)")
    parser.add_argument("--zoom", type=float, nargs=4, metavar=("HMIN", "HMAX", "VMIN", "VMAX"),
                        help="also draw this close-up window in a second panel")
    parser.add_argument("--title", default=None, help="picture title")
    parser.add_argument("--size", type=parse_size, default=(1600, 1000), help="pixels, WIDTHxHEIGHT")
    parser.add_argument("-o", "--output", required=True, help="PNG file to write")
    arguments = parser.parse_args()

    try:
        mesh = meshio.read(arguments.mesh)
    except Exception as error:  # meshio raises many types; report one line
        sys.exit(f"plot-mesh-cut: {arguments.mesh}: cannot read: {error}")
    points = np.asarray(mesh.points, dtype=float)
    if points.shape[1] < 3:
        sys.exit(f"plot-mesh-cut: {arguments.mesh}: not a 3D mesh")
    normal_axis, (first, second) = AXES[arguments.axis]
    position = arguments.position
    if position is None:
        position = 0.5 * (points[:, normal_axis].min() + points[:, normal_axis].max())
    window = arguments.window
    for name, box in (("--window", window), ("--zoom", arguments.zoom)):
        if box is not None and (box[0] >= box[1] or box[2] >= box[3]):
            sys.exit(f"plot-mesh-cut: {name} needs HMIN < HMAX and VMIN < VMAX")
    if window is not None and arguments.zoom is not None:
        # The close-up may reach outside the overview: cut the cells of both.
        window = [min(window[0], arguments.zoom[0]), max(window[1], arguments.zoom[1]),
                  min(window[2], arguments.zoom[2]), max(window[3], arguments.zoom[3])]

    # Blocks of one type (Gmsh writes one per volume) are drawn and counted together.
    polygons_by_type = {cell_type: [] for cell_type in CELL_COLOURS}
    for block in mesh.cells:
        if block.type in CELL_COLOURS:
            polygons_by_type[block.type] += cut_polygons(points, np.asarray(block.data), block.type,
                                                         arguments.axis, position, window)
    if not any(polygons_by_type.values()):
        sys.exit(f"plot-mesh-cut: no volume cell crosses the plane {arguments.axis} = {position:g}")
    legend = [Patch(facecolor=colour, edgecolor="black", linewidth=0.5,
                    label=f"{label} ({len(polygons_by_type[cell_type])})")
              for cell_type, (label, colour) in CELL_COLOURS.items() if polygons_by_type[cell_type]]

    width, height = arguments.size
    dpi = 100
    panels = [("overview", arguments.window)]
    if arguments.zoom is not None:
        panels.append(("close-up", arguments.zoom))
    figure, axes_list = plt.subplots(1, len(panels), figsize=(width / dpi, height / dpi), dpi=dpi, squeeze=False)
    for axes, (name, box) in zip(axes_list[0], panels):
        for cell_type, (label, colour) in CELL_COLOURS.items():
            if polygons_by_type[cell_type]:
                axes.add_collection(PolyCollection(polygons_by_type[cell_type], facecolors=[colour],
                                                   edgecolors="black", linewidths=0.25 if name == "overview" else 0.4))
        if box is not None:
            axes.set_xlim(box[0], box[1])
            axes.set_ylim(box[2], box[3])
        else:
            axes.autoscale_view()
        axes.set_aspect("equal", adjustable="box" if box is not None else "datalim")
        axes.set_xlabel(f"{AXIS_NAMES[first]} [m]")
        axes.set_ylabel(f"{AXIS_NAMES[second]} [m]")
        if len(panels) > 1:
            axes.set_title(name)
        if name == "close-up":
            overview = axes_list[0][0]
            box = arguments.zoom
            overview.add_patch(Rectangle((box[0], box[2]), box[1] - box[0], box[3] - box[2], fill=False,
                                         edgecolor="black", linewidth=1.2, linestyle="--"))
    figure.suptitle(arguments.title or f"{os.path.basename(arguments.mesh)}: cut {arguments.axis} = {position:g}")
    figure.legend(handles=legend, loc="center right", title="cells in the cut")
    figure.tight_layout(rect=(0.0, 0.0, 0.86, 1.0))  # room for the legend on the right
    figure.savefig(arguments.output, dpi=dpi)
    plt.close(figure)


if __name__ == "__main__":
    main()
