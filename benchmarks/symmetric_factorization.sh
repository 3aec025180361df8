#!/bin/bash
# What MUMPS' symmetric L D L^T factorization ('Linear solver/MUMPS
# symmetric factorization = true') gains over its L U (false, the default)
# on the same runs, in one run of this script:
#   box        parameters/box_3d_drag.prm as simplex 30 x 8 x 8 (9,600
#              tetrahedra, 7,533 unknowns), backward Euler, dt = 0.01, 10
#              steps;
#   box-nodal  the same with 'Formulation = nodal dilatation' (its
#              symmetric indefinite saddle-point system, 5 unknowns per
#              vertex);
#   beam       SOFA's small beam (parameters/sofa/beam_small.prm, 18,954
#              tetrahedra, 12,000 unknowns) by backward Euler with MUMPS,
#              0.1 s (10 steps).
# Per run (from its run.txt): the linear solves' wall time per Newton
# iteration (ms; factorizations and triangular solves), the median wall
# time per step (ms), the peak resident memory (MB); then the ratio L D
# L^T / L U of each. The answers agree to the Newton tolerance (the
# displacement at the end is compared: relative difference printed).
#
# Usage (from the repository top, after building):
#   bash benchmarks/symmetric_factorization.sh [path/to/tissuefem]
source "$(dirname "$0")/common.sh"

measure() { # mode, prm, settings...: prints solve/it (ms), median (ms), memory (MB), energy
  local mode=$1
  shift
  "$exe" "$@" --set "Output/VTU/Interval=0" --set "Output/Directory=$mode" \
    --set "Linear solver/Type=MUMPS" \
    --set "Linear solver/MUMPS symmetric factorization=$mode" \
    > "$mode.log" 2>&1 || { tail -3 "$mode.log" >&2; exit 1; }
  echo "$(value "$mode" "wall solve") $(value "$mode" "newton iterations") $(value "$mode" "step median") $(value "$mode" "peak memory") $(value "$mode" "stored energy")" |
    awk '{printf "%.2f %.2f %.0f %.17g\n", 1e3*$1/$2, 1e3*$3, $4, $5}'
}

printf '%-10s %-12s %12s %10s %10s %16s\n' scene factorization "solve/it ms" "median ms" "memory MB" "energy rel. diff"
for scene in box box-nodal beam; do
  case $scene in
    box|box-nodal)
      settings=("$top/parameters/box_3d_drag.prm"
                --set "Geometry/Cell type=simplex" --set "Geometry/Subdivisions=30, 8, 8"
                --set "Time integration/Time step=0.01" --set "Time integration/End time=0.1")
      [ $scene = box-nodal ] && settings+=(--set "Materials/Formulation=nodal dilatation") ;;
    beam)
      settings=("$top/parameters/sofa/beam_small.prm"
                --set "Time integration/Integrator=backward Euler"
                --set "Time integration/End time=0.1") ;;
  esac
  read -r -a lu < <(measure false "${settings[@]}")
  read -r -a ldlt < <(measure true "${settings[@]}")
  printf '%-10s %-12s %12s %10s %10s\n' "$scene" "L U" "${lu[@]:0:3}"
  printf '%-10s %-12s %12s %10s %10s %16s\n' "$scene" "L D L^T" "${ldlt[@]:0:3}" \
    "$(awk -v a="${ldlt[3]}" -v b="${lu[3]}" 'BEGIN {d = (a - b) / b; printf "%.1e", d < 0 ? -d : d}')"
  awk -v s="$scene" -v a="${ldlt[*]}" -v b="${lu[*]}" 'BEGIN {
    split(a, x, " "); split(b, y, " ")
    printf "%-10s %-12s %12.2f %10.2f %10.2f\n", s, "ratio", x[1] / y[1], x[2] / y[2], x[3] / y[3] }'
done
