#!/bin/bash
# Cook's membrane (parameters/cook_membrane.prm) on triangulations of the
# same N x N grid (default 64), and on an unstructured Gmsh mesh of about
# as many triangles: the tip deflection u_y at (48, 60) (length units) as a
# ratio to the converged answer, for
#   P1 at nu = 0.3      nothing locks: the error of the linear triangle's
#                       shear and bending on this mesh, the floor no
#                       volumetric treatment can go below;
#                       converged answer 7.7813 (Q2 on 32..256 x 256,
#                       Aitken, doc/studies.md), same Young's modulus;
#   P1 at nu = 0.4999   plain linear triangles, which lock;
#   P1-nodal            'Materials/Formulation = nodal dilatation' at
#                       nu = 0.4999; converged answer 6.9347 (FEniCS
#                       Taylor-Hood, doc/studies.md);
#   P1-pressure         'Materials/Formulation = nodal pressure' (one
#                       pressure per vertex, projection-stabilized, its
#                       default factor) at nu = 0.4999, same answer;
# and the wall time of the three nu = 0.4999 runs (s). Triangulations:
# deal.II's split of the grid ('Cell type = simplex', as the tests use), the
# four splits written by cook_triangulations.py (one diagonal each way,
# both diagonals around a centre node, alternating diagonals) and, where
# gmsh is installed (Debian package gmsh), a Delaunay mesh of mesh size
# 41.6 / N.
#
# With FACTORS set (e.g. FACTORS="1 2 4 8 16"), a second table gives the
# nodal pressure's tip ratio on each mesh for each 'Materials/Nodal
# pressure/Stabilization factor'.
#
# Usage (from the repository top, after building):
#   [FACTORS="..."] bash parameters/studies/cook_triangulations.sh [path/to/tissuefem] [N]
set -euo pipefail
exe=$(realpath "${1:-build/tissuefem}")
n=${2:-64}
here=$(realpath "$(dirname "$0")")
prm=$(realpath "$here/../cook_membrane.prm")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

run() { # formulation, Poisson's ratio, geometry settings...: prints tip and wall
  local formulation=$1 nu=$2
  shift 2
  local start
  start=$(date +%s.%N)
  "$exe" "$prm" "$@" --set "Materials/Formulation=$formulation" \
    --set "Materials/Poisson's ratio=$nu" \
    --set "Output/VTU/Interval=0" --set "Output/Directory=out" > log.txt 2>&1
  echo "$(tail -1 out/probes.csv | cut -d, -f6) $(echo "$(date +%s.%N) - $start" | bc)"
}

declare -A factor_row
meshes="deal.II right left crossed alternating"
if command -v gmsh > /dev/null; then
  meshes="$meshes gmsh"
fi
printf '%-12s %7s %9s %9s %9s %11s %24s\n' mesh cells "P1 0.3" "P1" "P1-nodal" "P1-pressure" \
  "wall P1, nodal, pressure"
for mesh in $meshes; do
  if [ "$mesh" = deal.II ]; then
    geometry=(--set "Geometry/Cell type=simplex" --set "Geometry/Subdivisions=$n, $n")
  else
    if [ "$mesh" = gmsh ]; then
      cat > cook.geo << GEO
lc = 41.6 / $n;
Point(1) = {0, 0, 0, lc}; Point(2) = {48, 44, 0, lc};
Point(3) = {48, 60, 0, lc}; Point(4) = {0, 44, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1}; Physical Surface(1) = {1};
GEO
      gmsh -2 -format msh22 cook.geo -o "$mesh.msh" > /dev/null
    else
      /usr/bin/env python3 "$here/cook_triangulations.py" "$mesh" "$n" "$mesh.msh"
    fi
    geometry=(--set "Geometry/Source=file" --set "Geometry/Mesh file=$work/$mesh.msh"
              --set "Geometry/Boundary id predicates=0: x < 1e-6 | 1: x > 48 - 1e-6")
  fi
  read -r compressible _ < <(run displacement 0.3 "${geometry[@]}")
  read -r locked wall_p1 < <(run displacement 0.4999 "${geometry[@]}")
  cells=$(sed -n 's/.* \([0-9]*\) cells,.*/\1/p' log.txt | head -1)
  read -r nodal wall_nodal < <(run "nodal dilatation" 0.4999 "${geometry[@]}")
  read -r pressure wall_pressure < <(run "nodal pressure" 0.4999 "${geometry[@]}")
  printf '%-12s %7s %9.4f %9.4f %9.4f %11.4f %10.1f, %5.1f, %5.1f\n' "$mesh" "$cells" \
    "$(echo "$compressible / 7.7813" | bc -l)" "$(echo "$locked / 6.9347" | bc -l)" \
    "$(echo "$nodal / 6.9347" | bc -l)" "$(echo "$pressure / 6.9347" | bc -l)" \
    "$wall_p1" "$wall_nodal" "$wall_pressure"
  factor_row[$mesh]=""
  for factor in ${FACTORS:-}; do
    read -r tip _ < <(run "nodal pressure" 0.4999 "${geometry[@]}" \
      --set "Materials/Nodal pressure/Stabilization factor=$factor")
    factor_row[$mesh]+=$(printf ' %9.4f' "$(echo "$tip / 6.9347" | bc -l)")
  done
done
if [ -n "${FACTORS:-}" ]; then
  echo
  echo "P1-pressure at nu = 0.4999, tip / 6.9347, by stabilization factor:"
  printf '%-12s' mesh
  for factor in $FACTORS; do printf ' %9s' "$factor"; done
  printf '\n'
  for mesh in $meshes; do printf '%-12s%s\n' "$mesh" "${factor_row[$mesh]}"; done
fi
