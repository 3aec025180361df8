#!/bin/bash
# What the locking-free linear simplices ('Materials/Formulation = nodal
# dilatation' and 'nodal pressure') cost against plain P1 ('displacement') on the same mesh, in
# one run of this script, for the scenes of issue 30's target (at most 2
# times plain P1):
#   liver  parameters/liver_incompressible.prm with P1 (SOFA's liver, 596
#          tetrahedra, nu = 0.495, backward Euler, dt = 0.02, 10 steps);
#   box    parameters/box_3d_drag.prm as simplex 30 x 8 x 8 (9,600
#          tetrahedra, nu = 0.45, backward Euler, dt = 0.01, 10 steps).
# Per run (from its run.txt): the median and 95th percentile of the wall
# time per step (ms), Newton iterations, and per Newton iteration the
# assembly and the linear solve (ms, the default direct solver); then the
# ratio nodal / P1 of each, both with the defaults (MUMPS factorizes plain
# P1's matrix as L U and the nodal dilatation's symmetric saddle-point
# system as L D L^T: 'Linear solver/MUMPS symmetric factorization =
# automatic'). Then the nodal dilatation again with L U ('... = false') and
# its ratio to plain P1; and the four-unknown element ('Formulation = nodal
# pressure', MUMPS L D L^T) and its ratio. Whole runs, one process, the
# machine's threads.
#
# Usage (from the repository top, after building):
#   bash benchmarks/nodal_dilatation_cost.sh [path/to/tissuefem] [repeats]
# Each run is repeated (default 3 times, the formulations interleaved) and
# every figure is the median over the repeats: the shared machine's load
# moves single runs by a third.
source "$(dirname "$0")/common.sh"
repeats=${2:-3}

measure() { # prm, settings...: prints median p95 newton assembly solve (ms) run (s)
  "$exe" "$@" --set "Output/VTU/Interval=0" --set "Output/Directory=out" \
    > log.txt 2>&1 || { tail -3 log.txt >&2; exit 1; }
  local its
  its=$(value out "newton iterations")
  echo "$(value out "step median") $(value out "step p95") $its $(value out "wall assembly") $(value out "wall solve") $(value out "wall total")" |
    awk -v n="$its" '{printf "%.2f %.2f %d %.2f %.2f %.2f\n", 1e3*$1, 1e3*$2, $3, 1e3*$4/n, 1e3*$5/n, $6}'
}

medians() { # file of measure() lines: the median of each column
  /usr/bin/env python3 -c '
import statistics, sys
rows = [list(map(float, line.split())) for line in open(sys.argv[1])]
print(" ".join("%.2f" % statistics.median(c) for c in zip(*rows)))' "$1"
}

ratio_row() { # label, name of the array divided by plain's
  local -n over=$2
  printf '%-6s %-18s' "$scene" "$1"
  for k in 0 1 2 3 4 5; do
    printf ' %*.2f' $([ $k -le 1 ] && echo 10 || ([ $k = 2 ] && echo 7 || ([ $k = 5 ] && echo 8 || echo 14))) \
      "$(echo "${over[$k]} / ${plain[$k]}" | bc -l)"
  done
  printf '\n'
}

printf '%-6s %-18s %10s %10s %7s %14s %14s %8s\n' scene formulation "median ms" "p95 ms" Newton \
  "assembly/it ms" "solve/it ms" "run s"
for scene in liver box; do
  if [ "$scene" = liver ]; then
    settings=("$top/parameters/liver_incompressible.prm"
              --set "Geometry/Mesh file=$top/data/liver.msh"
              --set "Finite element/Polynomial degree=1"
              --set "Time integration/End time=0.2")
  else
    settings=("$top/parameters/box_3d_drag.prm"
              --set "Geometry/Cell type=simplex" --set "Geometry/Subdivisions=30, 8, 8"
              --set "Time integration/Time step=0.01" --set "Time integration/End time=0.1")
  fi
  # Repeats interleaved, each figure the median over them.
  rm -f plain.txt nodal.txt lu.txt pressure.txt
  for ((k = 0; k < repeats; ++k)); do
    measure "${settings[@]}" --set "Materials/Formulation=displacement" >> plain.txt
    measure "${settings[@]}" --set "Materials/Formulation=nodal dilatation" >> nodal.txt
    measure "${settings[@]}" --set "Materials/Formulation=nodal dilatation" \
      --set "Linear solver/MUMPS symmetric factorization=false" >> lu.txt
    measure "${settings[@]}" --set "Materials/Formulation=nodal pressure" >> pressure.txt
  done
  read -r -a plain < <(medians plain.txt)
  read -r -a nodal < <(medians nodal.txt)
  read -r -a lu < <(medians lu.txt)
  read -r -a pressure < <(medians pressure.txt)
  printf '%-6s %-18s %10s %10s %7s %14s %14s %8s\n' "$scene" "P1" "${plain[@]}"
  printf '%-6s %-18s %10s %10s %7s %14s %14s %8s\n' "$scene" "P1-nodal" "${nodal[@]}"
  ratio_row "ratio (target 2)" nodal
  printf '%-6s %-18s %10s %10s %7s %14s %14s %8s\n' "$scene" "P1-nodal L U" "${lu[@]}"
  ratio_row "ratio L U / P1" lu
  printf '%-6s %-18s %10s %10s %7s %14s %14s %8s\n' "$scene" "P1-pressure" "${pressure[@]}"
  ratio_row "ratio (target 2)" pressure
done
