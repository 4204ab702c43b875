#!/usr/bin/python3
"""Independent check of near-wall orthogonality after a deformation of a planar mesh.

For every node of the wall marker, the grid line leaving the wall is the edge to a
non-boundary node most nearly along the wall normal in the original mesh; the script
prints the angle between that edge and the wall normal before and after, at the
leading edge (the wall node of smallest x) and the largest change over the wall, and
fails when the change exceeds --at-most degrees.

    deform_wall_angles.py ORIGINAL.msh DEFORMED.vtu --marker airfoil --at-most 2
"""
import argparse
import sys

import meshio
import numpy


def wall_edges(mesh, marker):
    names = {int(tag): name for name, (tag, _) in mesh.field_data.items()}
    edges = []
    for block, tags in zip(mesh.cells, mesh.cell_data["gmsh:physical"]):
        if block.type == "line":
            edges += [edge for edge, tag in zip(block.data, tags) if names.get(int(tag)) == marker]
    return numpy.array(edges)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("original")
    parser.add_argument("deformed")
    parser.add_argument("--marker", default="airfoil")
    parser.add_argument("--at-most", type=float, default=2.0)
    arguments = parser.parse_args()
    original = meshio.read(arguments.original)
    deformed = meshio.read(arguments.deformed)
    # Points of the original that cells use, in order (the reader drops unused ones).
    used = numpy.unique(numpy.concatenate([b.data.ravel() for b in original.cells if b.type in ("triangle", "quad")]))
    before = original.points[used, :2]
    after = deformed.points[:, :2]
    if len(after) != len(before):
        sys.exit("point counts differ: %d original, %d deformed" % (len(before), len(after)))
    renumber = -numpy.ones(len(original.points), dtype=int)
    renumber[used] = numpy.arange(len(used))
    walls = renumber[wall_edges(original, arguments.marker)]
    cells = [renumber[b.data] for b in original.cells if b.type in ("triangle", "quad")]
    boundary = set(renumber[numpy.concatenate([b.data.ravel() for b in original.cells if b.type == "line"])])
    neighbours = {}
    for block in cells:
        for k in range(block.shape[1]):
            for a, b in zip(block[:, k], block[:, (k + 1) % block.shape[1]]):
                neighbours.setdefault(a, set()).add(b)
                neighbours.setdefault(b, set()).add(a)

    def normals(points):
        result = {}
        centre = points[list(set(walls.ravel()))].mean(axis=0)
        for a, b in walls:
            along = points[b] - points[a]
            normal = numpy.array([-along[1], along[0]])
            normal /= numpy.linalg.norm(normal)
            if numpy.dot(normal, 0.5 * (points[a] + points[b]) - centre) < 0:  # away from the body
                normal = -normal
            for node in (a, b):
                result[node] = result.get(node, 0) + normal
        return {node: n / numpy.linalg.norm(n) for node, n in result.items()}

    def angle(points, node, end, normal):
        edge = points[end] - points[node]
        return numpy.degrees(numpy.arccos(numpy.clip(numpy.dot(edge, normal) / numpy.linalg.norm(edge), -1, 1)))

    normal_before, normal_after = normals(before), normals(after)
    changes = {}
    for node in normal_before:
        candidates = [n for n in neighbours.get(node, ()) if n not in boundary]
        if not candidates:
            continue
        end = min(candidates, key=lambda n: angle(before, node, n, normal_before[node]))
        changes[node] = (angle(before, node, end, normal_before[node]), angle(after, node, end, normal_after[node]))
    leading = min(changes, key=lambda node: before[node][0])
    worst = max(changes, key=lambda node: abs(changes[node][1] - changes[node][0]))
    print("leading edge (%.4f, %.4f): wall-line angle %.3f deg before, %.3f deg after, change %.3f deg" %
          (before[leading][0], before[leading][1], changes[leading][0], changes[leading][1],
           abs(changes[leading][1] - changes[leading][0])))
    print("largest change over %d wall nodes: %.3f deg at (%.4f, %.4f)" %
          (len(changes), abs(changes[worst][1] - changes[worst][0]), before[worst][0], before[worst][1]))
    if abs(changes[worst][1] - changes[worst][0]) > arguments.at_most:
        sys.exit("wall-line angle change above %g deg" % arguments.at_most)


if __name__ == "__main__":
    main()
