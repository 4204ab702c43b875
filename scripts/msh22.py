"""Writes a volume mesh in Gmsh's MSH 2.2 ASCII format, the format the case generators
in cases/ (wing/make_wing.py, cmesh/make_cmesh.py) hand to `mixmesh deform`."""


def write_msh22(path, points, elements, physical):
    """points: rows x, y, z; elements: (Gmsh element type, physical name, 0-based node
    indices); physical: name -> (dimension, tag), written as the $PhysicalNames."""
    with open(path, "w") as stream:
        stream.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n" % len(physical))
        for name, (dimension, tag) in physical.items():
            stream.write('%d %d "%s"\n' % (dimension, tag, name))
        stream.write("$EndPhysicalNames\n$Nodes\n%d\n" % len(points))
        for index, (x, y, z) in enumerate(points, 1):
            stream.write("%d %.17g %.17g %.17g\n" % (index, x, y, z))
        stream.write("$EndNodes\n$Elements\n%d\n" % len(elements))
        for index, (kind, name, nodes) in enumerate(elements, 1):
            tag = physical[name][1]
            stream.write("%d %d 2 %d %d %s\n" % (index, kind, tag, tag, " ".join(str(n + 1) for n in nodes)))
        stream.write("$EndElements\n")
