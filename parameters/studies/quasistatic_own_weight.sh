#!/bin/bash
# Organs under their own weight asked for in one quasistatic step (End
# time = Time step = 1), each way of getting there: the default load factor
# (automatic: t / End time, the failed step halved), 'Load factor = 1' (the
# loads constant in time, carried by load continuation), and each of these
# with 'Newton solver/Globalization = trust region' instead of the energy
# line search. Meshes: SOFA's Armadillo (4,406 tetrahedra) standing on its
# soles (y < -4.4 clamped) and hanging by its head (y > 8.5), SOFA's liver
# (596) and liver2 (1,493) hanging from their tops; robust neo-Hookean,
# E = 3000, nu = 0.3, rho = 1, g = 9.81; MUMPS.
#
# Prints per run: the exit status, the steps taken, the step attempts that
# failed, the Newton iterations (all attempts) and the wall time of the
# whole run (s). The same equilibrium is reached every way (the final
# elastic energy column agrees to its 8 digits); unit/quasistatic_own_weight
# checks that each clamp carries the weight.
#
# Usage (from the repository top, after building):
#   bash parameters/studies/quasistatic_own_weight.sh [path/to/tissuefem]
set -euo pipefail
exe=$(realpath "${1:-build/tissuefem}")
data=$(realpath "$(dirname "$0")/../../data")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

scene() {
  cat > scene.prm <<PRM
set Dimension = 3
subsection Geometry
  set Source                 = file
  set Mesh file              = $data/$1
  set Boundary id predicates = 7: $2
end
subsection Materials
  set Model           = robust neo-Hookean
  set Young's modulus = 3000
  set Poisson's ratio = 0.3
end
subsection Boundary conditions
  set Dirichlet = 7: xyz: 0; 0; 0
  set Gravity   = 0, -9.81, 0
end
subsection Time integration
  set Integrator = quasistatic
  set End time   = 1
  set Time step  = 1
end
subsection Output
  set Directory = out
  subsection VTU
    set Interval = 0
  end
end
PRM
}

printf '%-20s %-14s %-12s %5s %6s %7s %7s %9s %14s\n' organ "load factor" \
  globalization exit steps failed Newton "wall (s)" "final energy"
while read -r organ mesh clamp; do
  scene "$mesh" "${clamp//_/ }"
  for factor in automatic 1; do
    for globalization in "line search" "trust region"; do
      start=$(date +%s.%N)
      status=0
      "$exe" scene.prm --set "Boundary conditions/Load factor=$factor" \
        --set "Newton solver/Globalization=$globalization" > log.txt 2>&1 \
        || status=$?
      wall=$(echo "$(date +%s.%N) - $start" | bc)
      steps=$(grep -c '^step' log.txt || true)
      failed=$(grep -c 'retrying' log.txt || true)
      newton=$(awk '/^step/ {s += $10} END {print s + 0}' log.txt)
      energy=$(awk '/^final elastic energy/ {print $4}' log.txt)
      printf '%-20s %-14s %-12s %5s %6s %7s %7s %9.2f %14s\n' "$organ" \
        "$factor" "$globalization" "$status" "$steps" "$failed" "$newton" \
        "$wall" "${energy:--}"
    done
  done
done <<LIST
Armadillo-standing Armadillo_Tetra_4406.vtu y_<_-4.4
Armadillo-hanging Armadillo_Tetra_4406.vtu y_>_8.5
liver liver.msh y_>_4.2
liver2 liver2.msh y_>_0.45
LIST
