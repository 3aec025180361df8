#!/bin/bash
# Cost and accuracy of the elements for SOFA's liver (data/liver.msh, 596
# tetrahedra, parameters/liver_incompressible.prm) at rest under gravity:
# quasistatic, the load ramped by 'Load factor = t' in four steps, clamped
# at the top. For nu = 0.49 and 0.3, each element's unknowns, the
# displacement |u| of the lower lobe (probe 0, length units), its ratio to
# P2-P0 F-bar's, and the wall time of the run (s) and its ratio to plain
# P1's, all measured in this one run.
#
# What it shows (measured 2026-11-25, 2 cores): at nu = 0.3, where nothing
# locks, plain P1 is already about 30 % short of P2 on this coarse mesh,
# so no linear element reaches P2-P0 within a few percent here; at nu =
# 0.49 plain P1 loses another half of its displacement to locking, which
# the nodal dilatation ('Formulation = nodal dilatation') and the nodal
# pressure ('Formulation = nodal pressure') give back.
#
# Refined meshes (measured 2026-11-25, doc/studies.md): with
# REFINEMENTS=1 or 2 every tetrahedron is split into 8 (4,768 and 38,144
# tetrahedra), to see where each element converges; ELEMENTS picks the
# elements (default all five; the ratio column needs P2-P0-F-bar).
#
# Usage (from the repository top, after building):
#   bash parameters/studies/linear_tetrahedra.sh [path/to/tissuefem]
#   REFINEMENTS=2 ELEMENTS="P1 P1-nodal" bash parameters/studies/linear_tetrahedra.sh
set -euo pipefail
exe=$(realpath "${1:-build/tissuefem}")
prm=$(realpath "$(dirname "$0")/../liver_incompressible.prm")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
refinements=${REFINEMENTS:-0}
read -r -a elements <<< "${ELEMENTS:-P2-P0-F-bar P1 P1-nodal P1-pressure P2}"

# run NAME NU: prints "unknowns |u| seconds".
run() {
  local name=$1 nu=$2
  local args=(--set "Materials/Poisson's ratio=$nu" --set "Time integration/Integrator=quasistatic"
              --set "Time integration/Time step=0.25" --set "Boundary conditions/Load factor=t"
              --set "Output/VTU/Interval=0" --set "Output/Directory=$work/$name-$nu"
              --set "Geometry/Global refinements=$refinements")
  case $name in
    P1) args+=(--set "Finite element/Polynomial degree=1" --set "Materials/Formulation=displacement") ;;
    P1-nodal) args+=(--set "Finite element/Polynomial degree=1" --set "Materials/Formulation=nodal dilatation") ;;
    P1-pressure) args+=(--set "Finite element/Polynomial degree=1" --set "Materials/Formulation=nodal pressure") ;;
    P2) args+=(--set "Materials/Formulation=displacement") ;;
    P2-P0-F-bar) ;;
  esac
  local start end
  start=$(date +%s.%N)
  "$exe" "$prm" "${args[@]}" > "$work/log" 2>&1 || { echo "failed failed failed"; return; }
  end=$(date +%s.%N)
  local unknowns
  unknowns=$(grep -o '[0-9]* unknowns' "$work/log" | head -1 | cut -d' ' -f1)
  # The last row of probe 0 (probes.csv: time, probe, X, Y, Z, ux, uy, uz).
  awk -F, -v n="$unknowns" -v s="$start" -v e="$end" \
    '$2 == 0 { u = sqrt($6 * $6 + $7 * $7 + $8 * $8) } END { printf "%s %.6f %.2f", n, u, e - s }' \
    "$work/$name-$nu/probes.csv"
}

for nu in 0.49 0.3; do
  echo
  echo "SOFA liver at rest under gravity, nu = $nu, $refinements global refinements: lower lobe |u| (length units)"
  printf '%-12s %9s %10s %12s %9s %12s\n' element unknowns '|u|' 'vs P2-P0' 'wall (s)' 'vs P1 wall'
  declare -A result=()
  for name in "${elements[@]}"; do
    result[$name]=$(run "$name" "$nu")
  done
  read -r _ reference _ <<< "${result[P2-P0-F-bar]:-x nan x}"
  read -r _ _ p1_wall <<< "${result[P1]:-x x nan}"
  for name in P1 P1-nodal P1-pressure P2 P2-P0-F-bar; do
    [ -n "${result[$name]:-}" ] || continue
    read -r n u wall <<< "${result[$name]}"
    awk -v name="$name" -v n="$n" -v u="$u" -v r="$reference" -v w="$wall" -v w1="$p1_wall" \
      'BEGIN { printf "%-12s %9s %10.4f %12.3f %9.2f %12.2f\n", name, n, u, u / r, w, w / w1 }'
  done
done
