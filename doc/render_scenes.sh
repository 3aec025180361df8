#!/bin/sh
# Runs each shipped elasticity scene (parameters/*.prm) and renders one
# snapshot of it with doc/render_snapshot.py into
# doc/figures/scenes/<scene>.png (640 x 480): the deformed body coloured by
# von Mises stress over its undeformed outline.
# Usage (from anywhere; the runs go to /tmp/tissuefem_scenes/<scene>):
#   sh doc/render_scenes.sh [path/to/tissuefem]
# Needs python3-vtk9, and xvfb and xauth where there is no X display:
#   apt-get install -y --no-install-recommends python3-vtk9 xvfb xauth
#
# Left out: benchmark_assembly.prm and benchmark_muscle_force.prm (assembly
# benchmarks, no time stepping) and poisson_1d.prm (not elasticity).
# Each scene runs with its own parameters, except for
#   jeffrey_muscle   End time 0.5 -> 0.2 s, the only scene shortened: the
#                    whole run takes about a minute on two cores, and the
#                    picture is the end of the pull (t = 0.2 s) anyway
#   VTU/Interval     set where the scene writes no fields (the studies,
#                    quasistatic_1d, manufactured) or writes too few
#                    (invertible_block re-inflates before its step 5)
set -u
top=$(cd "$(dirname "$0")/.." && pwd)
exe=${1:-$top/build/tissuefem}
case $exe in /*) ;; *) exe=$PWD/$exe ;; esac  # the runs work in $runs
runs=/tmp/tissuefem_scenes
figs=$top/doc/figures/scenes
if [ ! -x "$exe" ]; then
  echo "render_scenes: no executable $exe" >&2
  exit 2
fi
# Work in $runs, so that nothing a scene writes lands in the repository.
mkdir -p "$runs" "$figs" && cd "$runs" || exit 1
failed=

# scene NAME 'RENDER OPTIONS' [--set 'Subsection/Name=value' ...]
scene() {
  name=$1 options=$2
  shift 2
  rm -rf "${runs:?}/${name:?}"
  start=$(date +%s)
  nice -n 19 "$exe" "$top/parameters/$name.prm" \
    --set "Output/Directory=$runs/$name" "$@" > "$runs/$name.log" 2>&1
  status=$?
  if [ $status -ne 0 ]; then
    echo "$name: tissuefem exit status $status, see $runs/$name.log" >&2
    failed="$failed $name"
    return
  fi
  ran=$(($(date +%s) - start))
  # $options unquoted on purpose: one word per option
  # shellcheck disable=SC2086
  if ! nice -n 19 python3 "$top/doc/render_snapshot.py" "$runs/$name" \
         "$figs/$name.png" --size 640x480 $options; then
    failed="$failed $name"
    return
  fi
  kb=$(($(wc -c < "$figs/$name.png") / 1024))
  printf '%-26s ran %3d s  %s.png %3d KB\n' "$name" "$ran" "$name" "$kb"
  [ "$kb" -le 150 ] || echo "$name: the PNG is larger than 150 KB" >&2
}

# A step other than the last where the end shows little: bodies that come
# back to rest are shown while still deformed.
scene teran_2d_backward_euler ''
scene cook_membrane ''
# The spindle lies along z and is pulled along x: x up shows the pull.
scene jeffrey_muscle '--up x' --set 'Time integration/End time=0.2'
scene anisotropic_muscle ''
# The liver hangs along y (gravity -y): seen from the front.
scene liver_gravity '--view xy'
scene invertible_block '--step 1' --set 'Output/VTU/Interval=1'
scene box_3d_drag ''
# t = 0.1 s, the end of the drag; displacement, as the stress is all in the
# grasped corner and would leave the rest of the block one colour
scene jeffrey_block '--step 500 --field displacement'
scene inversion_recovery '--step 5'  # t = 0.012, still partly inverted
# t = 0.25 s, the probe 8 mm deep; displacement, spindle upright: the dent
# at the right and the bow away from it
scene muscle_palpation '--step 25 --field displacement --up z'
scene liver_incompressible '--view xy'
scene jeffrey_table_e1 '--step 1' --set 'Output/VTU/Interval=1'
scene jeffrey_timing '' --set 'Output/VTU/Interval=1'
scene stability_map '' --set 'Output/VTU/Interval=10'
scene manufactured '' --set 'Output/VTU/Interval=10'
# 1D, u = sin t everywhere (a rigid motion, stress at round-off): the bar
# moved by u = 1 at t = pi/2
scene quasistatic_1d '--step 31 --field displacement' \
  --set 'Output/VTU/Interval=1'

if [ -n "$failed" ]; then
  echo "render_scenes: failed:$failed" >&2
  exit 1
fi
