#!/usr/bin/python3
"""Independent check of mesh files written by mixmesh: reads each with meshio and
asserts its cell counts and that every prism has a positive volume; with --gmsh,
also has Gmsh open every .msh file and write it again.

    io_meshio_check.py [--gmsh GMSH] --expect tetra=1,pyramid=1,wedge=1,hexahedron=1 FILE...

meshio numbers prisms like Gmsh (bottom triangle 0-1-2 counter-clockwise seen from
the top) for every format except .su2, which meshio 5.0 passes through in VTK
order; the volume below undoes that for .su2.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import meshio
import numpy as np

# Outward faces of a prism in Gmsh/meshio order.
WEDGE_FACES = [(0, 2, 1), (3, 4, 5), (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)]


def prism_volumes(points, wedges):
    """Signed volumes by the divergence theorem over fan-triangulated faces."""
    volumes = np.zeros(len(wedges))
    for face in WEDGE_FACES:
        corners = points[wedges[:, list(face)]]            # (cells, k, 3)
        centre = corners.mean(axis=1)
        k = len(face)
        for i in range(k):
            a, b = corners[:, i], corners[:, (i + 1) % k]
            volumes += np.einsum("ij,ij->i", centre, np.cross(a, b)) / 6.0
    return volumes


def check(path, expected, gmsh):
    mesh = meshio.read(path)
    counts = {}
    for block in mesh.cells:
        counts[block.type] = counts.get(block.type, 0) + len(block.data)
    failures = []
    for cell_type, count in expected.items():
        if counts.get(cell_type, 0) != count:
            failures.append(f"{cell_type}: {counts.get(cell_type, 0)} cells, expected {count}")
    wedges = [block.data for block in mesh.cells if block.type == "wedge"]
    if wedges:
        wedges = np.concatenate(wedges)
        if path.endswith(".su2"):
            wedges = wedges[:, [0, 2, 1, 3, 5, 4]]
        volumes = prism_volumes(np.asarray(mesh.points, dtype=float), wedges)
        if (volumes <= 0).any():
            failures.append(f"{int((volumes <= 0).sum())} of {len(volumes)} prisms have non-positive volume")
    if gmsh and path.endswith(".msh"):
        with tempfile.TemporaryDirectory() as folder:
            out = os.path.join(folder, "copy.msh")
            run = subprocess.run([gmsh, "-0", path, "-o", out, "-format", "msh41"], capture_output=True, text=True)
            if run.returncode != 0 or not os.path.exists(out) or "Error" in run.stdout + run.stderr:
                failures.append("gmsh cannot read it: " + (run.stdout + run.stderr).strip().splitlines()[-1])
    summary = " ".join(f"{t}={c}" for t, c in sorted(counts.items()))
    print(f"{path}: {summary}: " + ("; ".join(failures) if failures else "ok"))
    return not failures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--gmsh", help="Gmsh executable: also open every .msh file with it")
    parser.add_argument("--expect", required=True, help="cell counts, e.g. tetra=1,wedge=1")
    parser.add_argument("files", nargs="+")
    arguments = parser.parse_args()
    expected = {key: int(value) for key, value in (item.split("=") for item in arguments.expect.split(","))}
    results = [check(path, expected, arguments.gmsh) for path in arguments.files]
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
