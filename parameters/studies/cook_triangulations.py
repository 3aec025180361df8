#!/usr/bin/env python3
"""Writes Cook's membrane as triangles in Gmsh 2.2 ASCII format: the
N x N grid of the trapezoid with corners (0, 0), (48, 44), (0, 44),
(48, 60) (bilinear map of the unit square, as 'Geometry/Corners' does),
each grid cell split in one of four ways:

  right     the diagonal from its lower left to its upper right corner
  left      the other diagonal
  crossed   both diagonals: four triangles around a node at the centre
  alternating  'right' and 'left' in a checkerboard (the union jack)

Usage: cook_triangulations.py PATTERN N FILE. Boundary ids are left to the
scene ('Geometry/Boundary id predicates'): x = 0 clamped, x = 48 loaded."""
import sys


def corner(xi, eta):
    p00, p10, p01, p11 = (0, 0), (48, 44), (0, 44), (48, 60)
    return tuple((1 - xi) * (1 - eta) * p00[k] + xi * (1 - eta) * p10[k]
                 + (1 - xi) * eta * p01[k] + xi * eta * p11[k]
                 for k in range(2))


def write(pattern, n, path):
    nodes = {}

    def node(key, xi, eta):
        if key not in nodes:
            nodes[key] = (len(nodes) + 1, corner(xi, eta))
        return nodes[key][0]

    triangles = []
    for j in range(n):
        for i in range(n):
            a = node((2 * i, 2 * j), i / n, j / n)
            b = node((2 * i + 2, 2 * j), (i + 1) / n, j / n)
            c = node((2 * i + 2, 2 * j + 2), (i + 1) / n, (j + 1) / n)
            d = node((2 * i, 2 * j + 2), i / n, (j + 1) / n)
            kind = pattern
            if pattern == "alternating":
                kind = "right" if (i + j) % 2 == 0 else "left"
            if kind == "right":
                triangles += [(a, b, c), (a, c, d)]
            elif kind == "left":
                triangles += [(a, b, d), (b, c, d)]
            elif kind == "crossed":
                m = node((2 * i + 1, 2 * j + 1), (i + 0.5) / n, (j + 0.5) / n)
                triangles += [(a, b, m), (b, c, m), (c, d, m), (d, a, m)]
            else:
                raise SystemExit("unknown pattern " + pattern)
    # Every triangle counterclockwise (the bilinear map keeps orientation).
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
        for number, (x, y) in sorted(nodes.values()):
            f.write("%d %.17g %.17g 0\n" % (number, x, y))
        f.write("$EndNodes\n$Elements\n%d\n" % len(triangles))
        for k, t in enumerate(triangles):
            f.write("%d 2 2 1 1 %d %d %d\n" % (k + 1, *t))
        f.write("$EndElements\n")


if __name__ == "__main__":
    write(sys.argv[1], int(sys.argv[2]), sys.argv[3])
