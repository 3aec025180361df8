#!/bin/bash
# Cook's membrane at nu = 0.4999 (parameters/cook_membrane.prm) on
# triangulations of the same N x N grid (default 64), for plain P1 and P1
# with the nodal dilatation ('Materials/Formulation = nodal dilatation'):
# the tip deflection u_y at (48, 60) (length units), its ratio to the
# limit 6.9347 (FEniCS Taylor-Hood, doc/studies.md), the cells and the wall
# time of the run (s). Triangulations: deal.II's split of the grid
# ('Cell type = simplex', as the tests use) and the four splits written by
# cook_triangulations.py (one diagonal each way, both diagonals around a
# centre node, alternating diagonals).
#
# Usage (from the repository top, after building):
#   bash parameters/studies/cook_triangulations.sh [path/to/tissuefem] [N]
set -euo pipefail
exe=$(realpath "${1:-build/tissuefem}")
n=${2:-64}
here=$(realpath "$(dirname "$0")")
prm=$(realpath "$here/../cook_membrane.prm")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
printf '%-12s %-18s %7s %11s %7s %9s\n' mesh formulation cells "tip u_y" ratio "wall (s)"
for mesh in deal.II right left crossed alternating; do
  if [ "$mesh" = deal.II ]; then
    geometry=(--set "Geometry/Cell type=simplex" --set "Geometry/Subdivisions=$n, $n")
  else
    /usr/bin/env python3 "$here/cook_triangulations.py" "$mesh" "$n" "$mesh.msh"
    geometry=(--set "Geometry/Source=file" --set "Geometry/Mesh file=$work/$mesh.msh"
              --set "Geometry/Boundary id predicates=0: x < 1e-6 | 1: x > 48 - 1e-6")
  fi
  for formulation in displacement "nodal dilatation"; do
    start=$(date +%s.%N)
    "$exe" "$prm" "${geometry[@]}" --set "Materials/Formulation=$formulation" \
      --set "Output/VTU/Interval=0" --set "Output/Directory=out" > log.txt 2>&1
    wall=$(echo "$(date +%s.%N) - $start" | bc)
    cells=$(sed -n 's/.* \([0-9]*\) cells,.*/\1/p' log.txt | head -1)
    tip=$(tail -1 out/probes.csv | cut -d, -f6)
    printf '%-12s %-18s %7s %11.5f %7.4f %9.1f\n' "$mesh" "$formulation" "$cells" \
      "$tip" "$(echo "$tip / 6.9347" | bc -l)" "$wall"
  done
done
