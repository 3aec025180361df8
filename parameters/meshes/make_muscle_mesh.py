#!/usr/bin/env python3
"""Writes jeffrey_muscle.vtu next to this script: a spindle-shaped
(fusiform) muscle meshed with tetrahedra, close to the muscle of Jeffrey's
report (2552 tetrahedra, 861 nodes): here 850 nodes and 2640 tetrahedra.

Geometry (metres): axis along z from 0 to L = 0.15; circular cross-section
of radius r(z) = r_t + (r_b - r_t) sin(pi z / L), tendon radius r_t = 0.004,
belly radius r_b = 0.015.

Construction: a structured grid of (M+1) x (M+1) x (NZ+1) nodes (M = 4,
NZ = 33). Each cross-section maps the square [-1, 1]^2 onto the unit disc
(x = s sqrt(1 - t^2/2), y = t sqrt(1 - s^2/2)), scaled by r(z). Each grid
cube is split into 5 tetrahedra, the two mirror-image splits alternating
with the parity of i + j + k so that neighbouring cubes share face
diagonals (a conforming mesh). Every tetrahedron is written positively
oriented. No randomness: the file is reproducible.

The end faces z = 0 and z = L get boundary ids from predicates in
parameters/jeffrey_muscle.prm. Run: python3 make_muscle_mesh.py
"""

import math
import os
from collections import Counter

L, R_T, R_B = 0.15, 0.004, 0.015
M, NZ = 4, 33


def radius(z):
    return R_T + (R_B - R_T) * math.sin(math.pi * z / L)


def index(i, j, k):
    return i + (M + 1) * (j + (M + 1) * k)


points = []
for k in range(NZ + 1):
    z = L * k / NZ
    for j in range(M + 1):
        for i in range(M + 1):
            s, t = 2 * i / M - 1, 2 * j / M - 1
            x = s * math.sqrt(1 - t * t / 2)
            y = t * math.sqrt(1 - s * s / 2)
            points.append((radius(z) * x, radius(z) * y, z))

# Cube corners: c = a + 2b + 4c for offsets (a, b, c) in {0, 1}^3.
EVEN = [(0, 1, 2, 4), (1, 3, 2, 7), (1, 4, 5, 7), (2, 7, 6, 4), (1, 2, 4, 7)]
ODD = [(0, 1, 3, 5), (0, 2, 3, 6), (0, 4, 5, 6), (3, 5, 6, 7), (0, 3, 5, 6)]


def signed_volume(tet):
    a, b, c, d = (points[v] for v in tet)
    e = [[q[x] - a[x] for x in range(3)] for q in (b, c, d)]
    return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1])
            - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0])
            + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6


tets = []
for k in range(NZ):
    for j in range(M):
        for i in range(M):
            corner = [index(i + a, j + b, k + c)
                      for c in (0, 1) for b in (0, 1) for a in (0, 1)]
            for local in (EVEN if (i + j + k) % 2 == 0 else ODD):
                tet = [corner[n] for n in local]
                if signed_volume(tet) < 0:
                    tet[1], tet[2] = tet[2], tet[1]
                tets.append(tet)

# Checks: positive volumes, conformity, closed surface, volume.
volumes = [signed_volume(t) for t in tets]
assert min(volumes) > 0
faces = Counter(tuple(sorted(f)) for t in tets
                for f in ((t[0], t[1], t[2]), (t[0], t[1], t[3]),
                          (t[0], t[2], t[3]), (t[1], t[2], t[3])))
assert max(faces.values()) == 2
boundary = [f for f, n in faces.items() if n == 1]
edges = Counter(tuple(sorted(e)) for f in boundary
                for e in ((f[0], f[1]), (f[0], f[2]), (f[1], f[2])))
assert set(edges.values()) == {2}, "the surface is not closed"
exact = sum(math.pi * radius(L * (n + 0.5) / 2000) ** 2 * L / 2000
            for n in range(2000))
assert abs(sum(volumes) / exact - 1) < 0.1
lengths = [math.dist(points[t[a]], points[t[b]]) for t in tets
           for a in range(4) for b in range(a + 1, 4)]


def lines(values, per_line):
    return "\n".join("          " + " ".join(str(v) for v in values[s:s + per_line])
                     for s in range(0, len(values), per_line))


text = f"""<?xml version="1.0"?>
<!-- Spindle-shaped muscle for parameters/jeffrey_muscle.prm: {len(points)} nodes,
     {len(tets)} tetrahedra; written by make_muscle_mesh.py. -->
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="{len(points)}" NumberOfCells="{len(tets)}">
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">
{lines([f"{x:.12g} {y:.12g} {z:.12g}" for x, y, z in points], 1)}
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
      <CellData>
        <DataArray type="Int32" Name="MaterialIds" format="ascii">
{lines([0] * len(tets), 24)}
        </DataArray>
      </CellData>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
"""
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                       "jeffrey_muscle.vtu"), "w") as f:
    f.write(text)
print(f"{len(points)} nodes, {len(tets)} tetrahedra, {len(boundary)} boundary "
      f"triangles; volume {sum(volumes):.6g} m^3 (smooth spindle {exact:.6g}); "
      f"smallest tetrahedron {min(volumes):.3g} m^3; edges {min(lengths):.3g} to "
      f"{max(lengths):.3g} m")
