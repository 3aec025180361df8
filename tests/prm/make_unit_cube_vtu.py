#!/usr/bin/env python3
"""Writes unit_cube_tets.vtu next to this script: the unit cube [0,1]^3 as
2x2x2 small cubes, each split into 6 tetrahedra along its main diagonal
(Kuhn/Freudenthal split; every small cube is split the same way, so the
mesh is conforming). VTK XML UnstructuredGrid with ASCII data, as SOFA
ships organ meshes.

Every 7th tetrahedron is written inside out (two vertices swapped) so that
a reader's reorientation is exercised; all others have positive volume.
"""

import itertools
import os

N = 2  # small cubes per direction


def point_index(i, j, k):
    return i + (N + 1) * (j + (N + 1) * k)


def signed_volume(points, tet):
    a, b, c, d = (points[v] for v in tet)
    e = [[q[x] - a[x] for x in range(3)] for q in (b, c, d)]
    return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1])
            - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0])
            + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6


points = [(i / N, j / N, k / N)
          for k in range(N + 1) for j in range(N + 1) for i in range(N + 1)]

tets = []
for k, j, i in itertools.product(range(N), repeat=3):
    # One tetrahedron per order in which the path from the cube's lower
    # corner to its upper corner takes the three unit steps.
    for order in itertools.permutations(range(3)):
        corner = [i, j, k]
        tet = [point_index(*corner)]
        for axis in order:
            corner[axis] += 1
            tet.append(point_index(*corner))
        if signed_volume(points, tet) < 0:
            tet[1], tet[2] = tet[2], tet[1]
        tets.append(tet)

for n, tet in enumerate(tets):
    if n % 7 == 6:
        tet[1], tet[2] = tet[2], tet[1]

assert abs(sum(abs(signed_volume(points, t)) for t in tets) - 1) < 1e-12
n_inverted = sum(signed_volume(points, t) < 0 for t in tets)


def lines(values, per_line):
    return "\n".join("          " + " ".join(str(v) for v in values[s:s + per_line])
                     for s in range(0, len(values), per_line))


text = f"""<?xml version="1.0"?>
<!-- Unit cube, {len(tets)} tetrahedra ({n_inverted} deliberately inside out);
     written by make_unit_cube_vtu.py. -->
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="{len(points)}" NumberOfCells="{len(tets)}">
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">
{lines([f"{x:g} {y:g} {z:g}" for x, y, z in points], 1)}
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">
{lines([" ".join(map(str, t)) for t in tets], 1)}
        </DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">
{lines([4 * (n + 1) for n in range(len(tets))], 12)}
        </DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">
{lines([10] * len(tets), 24)}
        </DataArray>
      </Cells>
      <CellData Scalars="MaterialIds">
        <DataArray type="Int32" Name="MaterialIds" format="ascii">
{lines([0] * len(tets), 24)}
        </DataArray>
      </CellData>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
"""

with open(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                       "unit_cube_tets.vtu"), "w") as out:
    out.write(text)
print(f"wrote {len(points)} points, {len(tets)} tetrahedra, "
      f"{n_inverted} inside out")
