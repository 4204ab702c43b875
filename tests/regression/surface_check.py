#!/usr/bin/python3
"""Independent checks of a surface mesh written by `mixmesh surface` (.vtu), and of its errors.

    surface_check.py mesh FILE [--wing-faces N] [--symmetry-y 0]
        Reads FILE with VTK and checks: every wall edge (markers other than "wake")
        is shared by exactly two wall faces in opposite directions, except edges on the
        symmetry plane (used once); no zero-area face; the enclosed volume (divergence
        theorem, F = (0, 0, z)) is positive, so the normals point out; wake faces face +z
        and every wake edge on the trailing edge is a wall edge; optional wing face count.
    surface_check.py fails REGEX -- COMMAND...
        Runs COMMAND, expects a non-zero exit and one stderr line matching REGEX.
Exit 0 when every check passes, 1 otherwise.
"""
import re
import subprocess
import sys
from collections import Counter

import numpy as np


def check_mesh(path, wing_faces, symmetry_y):
    # VTK's own reader (meshio 5 misreads the integer field data of appended files).
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfPoints() == 0:
        print(f"{path}: no points")
        return 1
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    field = grid.GetFieldData()
    names = {}
    for k in range(field.GetNumberOfArrays()):
        array = field.GetArray(k)
        if array is not None and array.GetName().startswith("marker:"):
            names[int(array.GetValue(0))] = array.GetName().split(":", 1)[1]
    markers = vtk_to_numpy(grid.GetCellData().GetArray("marker"))
    faces = {"wall": [], "wake": []}
    for cell in range(grid.GetNumberOfCells()):
        if grid.GetCellType(cell) not in (5, 9):
            print(f"unexpected VTK cell type {grid.GetCellType(cell)}")
            return 1
        ids = grid.GetCell(cell).GetPointIds()
        nodes = [ids.GetId(k) for k in range(ids.GetNumberOfIds())]
        faces["wake" if names.get(int(markers[cell])) == "wake" else "wall"].append(nodes)
    failures = []
    directed = Counter()
    for face in faces["wall"]:
        for k in range(len(face)):
            directed[(face[k], face[(k + 1) % len(face)])] += 1
    on_plane = np.abs(points[:, 1] - symmetry_y) < 1e-12
    free = 0
    for (a, b), count in directed.items():
        if count != 1:
            failures.append(f"wall edge {a}-{b} used {count} times in one direction")
        if (b, a) not in directed:
            if not (on_plane[a] and on_plane[b]):
                free += 1
    if free:
        failures.append(f"{free} free wall edges off the symmetry plane")
    volume = 0.0
    smallest = np.inf
    for face in faces["wall"]:
        p = points[face]
        for k in range(1, len(face) - 1):
            cross = np.cross(p[k] - p[0], p[k + 1] - p[0])
            smallest = min(smallest, np.linalg.norm(cross))
            volume += 0.5 * cross[2] * (p[0, 2] + p[k, 2] + p[k + 1, 2]) / 3.0
    if not volume > 0.0:
        failures.append(f"enclosed volume {volume} is not positive: normals point inwards")
    if not smallest > 0.0:
        failures.append("degenerate wall face")
    wall_nodes = {node for face in faces["wall"] for node in face}
    for face in faces["wake"]:
        p = points[face]
        normal = np.cross(p[2] - p[0], p[3] - p[1])
        if not normal[2] > 0.0:
            failures.append(f"wake face {face} does not face +z")
            break
    attached = sum(1 for face in faces["wake"] if face[0] in wall_nodes and face[3] in wall_nodes)
    if faces["wake"] and attached == 0:
        failures.append("the wake does not start at the wing")
    quads = sum(1 for face in faces["wall"] if len(face) == 4)
    if wing_faces is not None and quads != wing_faces:
        failures.append(f"{quads} wing quads, expected {wing_faces}")
    print(f"{path}: {len(points)} points, {len(faces['wall'])} wall faces ({quads} quads), "
          f"{len(faces['wake'])} wake faces, volume {volume:.6g}")
    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


def check_failure(pattern, command):
    result = subprocess.run(command, capture_output=True, text=True)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    print("exit", result.returncode, "stderr:", result.stderr.strip())
    if result.returncode == 0:
        print("FAIL: the command succeeded")
        return 1
    if len(lines) != 1 or not re.search(pattern, lines[0]):
        print(f"FAIL: expected one stderr line matching {pattern!r}")
        return 1
    return 0


def main(arguments):
    if len(arguments) >= 2 and arguments[0] == "mesh":
        wing_faces = None
        symmetry_y = 0.0
        rest = arguments[2:]
        while rest:
            if rest[0] == "--wing-faces":
                wing_faces = int(rest[1])
            elif rest[0] == "--symmetry-y":
                symmetry_y = float(rest[1])
            rest = rest[2:]
        return check_mesh(arguments[1], wing_faces, symmetry_y)
    if len(arguments) >= 4 and arguments[0] == "fails" and arguments[2] == "--":
        return check_failure(arguments[1], arguments[3:])
    print(__doc__)
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
