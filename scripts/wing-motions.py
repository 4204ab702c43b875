#!/usr/bin/python3
"""Motion files for a generated wing mesh: pitch +15 and -15 degrees about x = CENTRE_X
(axis -y), a plunge of half the root chord (+z) and a bending mode (z = 0.15 b (y/b)^2,
tip twist 5 degrees nose up about x = CENTRE_X, linear in y/b), each for ARA and IDW,
one step from the mesh as generated. The wall marker is `wall`, the symmetry plane
`symmetry` (generate's defaults).

    /usr/bin/python3 scripts/wing-motions.py MESH OUTDIR CENTRE_X ROOT_CHORD SEMI_SPAN
    mixmesh deform MESH --motion OUTDIR/pitch+15_ara.toml -o pitch+15_ara.vtu

Writes OUTDIR/{pitch+15,pitch-15,plunge,bend}_{ara,idw}.toml and OUTDIR/bend.csv (the
mode file, `node,x,y,z` displacements of every wall node). Needs meshio and numpy.
"""
import os
import sys

import meshio
import numpy as np


def main():
    if len(sys.argv) != 6:
        sys.exit("usage: wing-motions.py MESH OUTDIR CENTRE_X ROOT_CHORD SEMI_SPAN")
    mesh, out = sys.argv[1], sys.argv[2]
    centre_x, root_chord, semi_span = (float(value) for value in sys.argv[3:6])
    os.makedirs(out, exist_ok=True)
    read = meshio.read(mesh)
    wall_marker = int(read.field_data["marker:wall"][0])
    wall = set()
    for block, markers in zip(read.cells, read.cell_data["marker"]):
        if block.type in ("triangle", "quad"):
            for nodes, marker in zip(block.data, markers):
                if marker == wall_marker:
                    wall.update(int(node) for node in nodes)
    wall = np.array(sorted(wall))
    head = 'method = "{method}"\nsteps = 1\nsymmetry = ["symmetry"]\n[[body]]\nname = "wing"\nmarkers = ["wall"]\n'
    for method in ("ara", "idw"):
        for angle in (15, -15):
            with open(f"{out}/pitch{angle:+d}_{method}.toml", "w") as file:
                file.write(head.format(method=method) + f'motion = "rigid"\ncentre = [{centre_x}, 0.0, 0.0]\n'
                           f"axis = [0.0, -1.0, 0.0]\nangle = {angle}.0\n")
        with open(f"{out}/plunge_{method}.toml", "w") as file:
            file.write(head.format(method=method) + f'motion = "rigid"\ntranslation = [0.0, 0.0, {0.5 * root_chord}]\n')
        with open(f"{out}/bend_{method}.toml", "w") as file:
            file.write(head.format(method=method) + 'motion = "mode"\nfile = "bend.csv"\nscale = 1.0\n')
    points = read.points[wall]
    eta = np.clip(points[:, 1] / semi_span, 0.0, None)
    twist = np.radians(5.0) * eta
    along = points[:, 0] - centre_x
    x = centre_x + along * np.cos(twist) + points[:, 2] * np.sin(twist)
    z = -along * np.sin(twist) + points[:, 2] * np.cos(twist) + 0.15 * semi_span * eta**2
    with open(f"{out}/bend.csv", "w") as file:
        file.write("node,x,y,z\n")
        for index, node in enumerate(wall):
            file.write(f"{node},{x[index] - points[index, 0]:.9g},0,{z[index] - points[index, 2]:.9g}\n")
    print(f"{len(wall)} wall nodes; wrote {out}/{{pitch+15,pitch-15,plunge,bend}}_{{ara,idw}}.toml and bend.csv")


if __name__ == "__main__":
    main()
