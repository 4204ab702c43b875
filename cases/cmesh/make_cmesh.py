#!/usr/bin/python3
"""Builds a structured C-mesh of the NACA 0012 (chord 1, closed trailing edge) as a
blockMesh-style case would have it: one block wrapped round the airfoil and its wake,
the wake cut an interior line where the grid lines leaving the wake's two sides meet,
the first cell 1e-5 chords high on the airfoil and on both sides of the cut, one cell
thick in z (hexahedra only) between the sliding planes front and back.

Writes OUTPUT (default cmesh.msh in the working folder; Gmsh 2.2; markers airfoil,
farfield, front, back).

    ./make_cmesh.py [--around 160] [--wake 48] [--normal 64] [--first-spacing 1e-5]
                    [--radius 10] [--wake-length 10] [--layer-height 0.05] [--thickness 0.05]
                    [--output cmesh.msh]

--around must be even (cells on each side of the airfoil); --output is taken relative
to the working folder.
"""
import argparse
import math
import pathlib
import sys

import numpy

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts"))
from msh22 import write_msh22  # noqa: E402


def naca0012(x):
    return 0.6 * (0.2969 * math.sqrt(x) - 0.1260 * x - 0.3516 * x ** 2 + 0.2843 * x ** 3 - 0.1036 * x ** 4)


def geometric(first, total, count):
    """count + 1 positions from 0 to total whose first step is `first`, each step the
    previous times a ratio r (solved by fixed-point iteration)."""
    ratio = 1.1
    for _ in range(500):
        ratio = (1.0 + (ratio - 1.0) * total / first) ** (1.0 / count)
    steps = first * ratio ** numpy.arange(count)
    return numpy.concatenate([[0.0], numpy.cumsum(steps) * total / steps.sum()])


def inner_line(around, wake, wake_length):
    """The C line from the wake's downstream end under the cut, round the airfoil
    (lower side, leading edge, upper side) and back along the cut: points and, for
    each, the side normal its grid line leaves by."""
    # Cosine spacing on each side of the airfoil: fine at both edges.
    half = around // 2
    x_side = 0.5 * (1.0 - numpy.cos(numpy.pi * numpy.arange(half + 1) / half))
    trailing_spacing = x_side[-1] - x_side[-2]
    x_wake = 1.0 + geometric(trailing_spacing, wake_length, wake)
    points = [(x, 0.0) for x in x_wake[:0:-1]]  # lower wake, downstream end first
    points += [(x, -naca0012(x)) for x in x_side[::-1]]  # lower side, trailing to leading edge
    points += [(x, naca0012(x)) for x in x_side[1:]]  # upper side back to the trailing edge
    airfoil = range(wake, wake + 2 * half + 1)
    points += [(x, 0.0) for x in x_wake[1:]]  # upper wake
    points = numpy.array(points)
    normals = numpy.zeros_like(points)
    normals[:wake] = (0.0, -1.0)
    normals[airfoil.stop:] = (0.0, 1.0)
    for index in airfoil:  # the curve's normal, away from the airfoil
        tangent = points[min(index + 1, airfoil.stop - 1)] - points[max(index - 1, airfoil.start)]
        normals[index] = (-tangent[1], tangent[0])
        normals[index] /= numpy.linalg.norm(normals[index])
    # Towards the trailing edge the lines turn to leave along the cut's normal, as the
    # wake's do (over the last fifth of the chord): the surface normals there lean back
    # by the trailing-edge half-angle and would cross the cut's lines a few cells off
    # the wall.
    for index in airfoil:
        x = points[index, 0]
        turn = min(1.0, max(0.0, (x - 0.8) / 0.2))
        normals[index] = (1.0 - turn) * normals[index] + turn * numpy.array([0.0, 1.0 if index >= airfoil.start + half else -1.0])
        normals[index] /= numpy.linalg.norm(normals[index])
    return points, normals, airfoil


def outer_line(points, normals, airfoil, radius):
    """The C-shaped outer boundary: straight under and over the wake at y = ±radius and
    a half circle round the front about the trailing edge. An airfoil point's outer
    point lies on the circle in the direction of its normal (so its line leaves the
    wall and reaches the far field without turning much), averaged with the point at
    its arc-length fraction and made monotone (so lines stay apart where the normals
    crowd, at the leading edge, and the trailing edge's lines keep their order)."""
    outer = numpy.zeros_like(points)
    for index in range(airfoil.start):
        outer[index] = (points[index, 0], -radius)
    for index in range(airfoil.stop, len(points)):
        outer[index] = (points[index, 0], radius)
    section = points[airfoil.start:airfoil.stop]
    length = numpy.concatenate([[0.0], numpy.cumsum(numpy.linalg.norm(numpy.diff(section, axis=0), axis=1))])
    # Angles about the trailing edge from -pi/2 (below) through -pi (ahead) to -3pi/2.
    by_length = -0.5 * math.pi - math.pi * length / length[-1]
    half = len(section) // 2  # the leading edge
    by_normal = numpy.zeros(len(section))
    for offset, normal in enumerate(normals[airfoil.start:airfoil.stop]):
        angle = math.atan2(normal[1], normal[0])  # lower side in [-pi, 0], upper in [0, pi]
        if offset < half:
            by_normal[offset] = min(angle if angle <= 0.0 else -math.pi, -0.5 * math.pi)
        elif offset > half:
            by_normal[offset] = max((angle if angle >= 0.0 else math.pi) - 2.0 * math.pi, -1.5 * math.pi)
        else:
            by_normal[offset] = -math.pi
    angles = 0.5 * (by_length + by_normal)
    angles[0], angles[-1] = -0.5 * math.pi, -1.5 * math.pi
    step = 0.1 * math.pi / len(angles)  # at least a tenth of the even step apart
    for index in range(1, len(angles)):
        angles[index] = min(angles[index], angles[index - 1] - step)
    angles[-1] = -1.5 * math.pi
    for index in range(len(angles) - 2, 0, -1):
        angles[index] = max(angles[index], angles[index + 1] + step)
    for offset, angle in enumerate(angles):
        outer[airfoil.start + offset] = (1.0 + radius * math.cos(angle), radius * math.sin(angle))
    return outer


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--around", type=int, default=160, help="cells round the airfoil")
    parser.add_argument("--wake", type=int, default=48, help="cells along the wake, each side")
    parser.add_argument("--normal", type=int, default=64, help="cells from the wall to the far field")
    parser.add_argument("--first-spacing", type=float, default=1e-5)
    parser.add_argument("--radius", type=float, default=10.0)
    parser.add_argument("--wake-length", type=float, default=10.0)
    parser.add_argument("--layer-height", type=float, default=0.05,
                        help="height over which the lines leave the wall along its normal")
    parser.add_argument("--thickness", type=float, default=0.05, help="extent in z")
    parser.add_argument("--output", default="cmesh.msh")
    arguments = parser.parse_args()
    if arguments.around < 4 or arguments.around % 2:
        parser.error("--around must be an even number of at least 4, not %d" % arguments.around)

    inner, normals, airfoil = inner_line(arguments.around, arguments.wake, arguments.wake_length)
    outer = outer_line(inner, normals, airfoil, arguments.radius)
    columns, rows = len(inner), arguments.normal + 1
    grid = numpy.zeros((columns, rows, 2))
    for column in range(columns):
        span = numpy.linalg.norm(outer[column] - inner[column])
        fractions = geometric(arguments.first_spacing / span, 1.0, arguments.normal)
        for row, s in enumerate(fractions):
            # Off the wall along the normal first, blended into the straight line to the
            # outer point over the layer height: orthogonal layers, a smooth far field.
            along_normal = inner[column] + normals[column] * s * span
            straight = (1.0 - s) * inner[column] + s * outer[column]
            blend = min(1.0, s * span / arguments.layer_height)
            grid[column, row] = (1.0 - blend) * along_normal + blend * straight

    # Nodes: the cut's lower and upper wall rows are one set of nodes (mirror columns).
    node_of = {}
    planar = []

    def node(column, row):
        if row == 0 and column >= airfoil.stop - 1:
            column = columns - 1 - column  # the upper side's cut node is the lower side's
        key = (column, row)
        if key not in node_of:
            node_of[key] = len(planar)
            planar.append(grid[column, row])
        return node_of[key]

    quads = []
    for column in range(columns - 1):
        for row in range(rows - 1):
            quad = [node(column, row), node(column + 1, row), node(column + 1, row + 1), node(column, row + 1)]
            corners = numpy.array([planar[n] for n in quad])
            area = sum(corners[k, 0] * corners[(k + 1) % 4, 1] - corners[(k + 1) % 4, 0] * corners[k, 1]
                       for k in range(4))
            quads.append(quad if area > 0 else quad[::-1])
    planar = numpy.array(planar)
    count = len(planar)
    points = numpy.vstack([numpy.column_stack([planar, numpy.full(count, z)]) for z in (0.0, arguments.thickness)])

    elements = [(5, "fluid", q + [n + count for n in q]) for q in quads]
    elements += [(3, "front", q[::-1]) for q in quads]
    elements += [(3, "back", [n + count for n in q]) for q in quads]

    def side(a, b, name):
        elements.append((3, name, [a, b, b + count, a + count]))

    for column in airfoil[:-1]:  # the wall: row 0 between the trailing edge's two visits
        side(node(column + 1, 0), node(column, 0), "airfoil")
    for column in range(columns - 1):  # the outer C
        side(node(column, rows - 1), node(column + 1, rows - 1), "farfield")
    for row in range(rows - 1):  # the two outlet ends
        side(node(0, row + 1), node(0, row), "farfield")
        side(node(columns - 1, row), node(columns - 1, row + 1), "farfield")

    # Wall and outlet faces must face out of the fluid: orient each side face against
    # the centre of its cell's planar quad.
    quad_of_edge = {}
    for quad in quads:
        for k in range(4):
            quad_of_edge[frozenset((quad[k], quad[(k + 1) % 4]))] = quad
    for index, (kind, name, nodes) in enumerate(elements):
        if name not in ("airfoil", "farfield"):
            continue
        a, b = nodes[0], nodes[1]
        centre = planar[quad_of_edge[frozenset((a, b))]].mean(axis=0)
        edge = planar[b] - planar[a]
        outward = numpy.array([edge[1], -edge[0]])  # right of a → b, for an anticlockwise quad's outside
        if numpy.dot(outward, 0.5 * (planar[a] + planar[b]) - centre) < 0:
            elements[index] = (kind, name, [b, a, a + count, b + count])

    physical = {"fluid": (3, 1), "front": (2, 2), "back": (2, 3), "farfield": (2, 4), "airfoil": (2, 5)}
    output = pathlib.Path(arguments.output)
    write_msh22(output, points, elements, physical)
    print("%s: %d points, %d hexahedra; first cell %.3g chords, %d x %d cells"
          % (output.name, len(points), len(quads), arguments.first_spacing, columns - 1, rows - 1))


if __name__ == "__main__":
    main()
