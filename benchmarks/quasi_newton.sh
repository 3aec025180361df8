#!/bin/bash
# The quasi-Newton backward Euler against Newton's backward Euler and the
# linearly implicit Euler, on three scenes, all in one run of this script:
#   box     the 9,600-tet box (box_3d_drag.prm, simplex 30 x 8 x 8,
#           robust neo-Hookean, dt = 0.01 s, 30 steps),
#   beam    SOFA's small beam (sofa/beam_small.prm: corotational, Rayleigh
#           damping, dt = 0.01 s, 50 steps),
#   muscle  Jeffrey's muscle (jeffrey_muscle.prm, transversely isotropic
#           St Venant-Kirchhoff, pulled by the grasping tool) at dt = 1/30 s
#           over 0.5 s.
# Per run: the median and 95th percentile of the step (ms), the whole run
# (s), the error: the largest distance over the run between the probe's
# displacement (the box's centre, the beam's free end, the muscle's belly) and that of converged backward Euler (MUMPS, Newton to
# 1e-12 relative) at the same times, relative to the reference's largest
# probe displacement (%), and the median step over backward Euler's with
# the scene's defaults ("/ BE").
#
# Usage (from the repository top, after building; about 5 minutes):
#   bash benchmarks/quasi_newton.sh [path/to/tissuefem] [box|beam|muscle|all]
source "$(dirname "$0")/common.sh"
which=${2:-all}

run() { # directory, settings...
  local dir=$1
  shift
  "$exe" "${scene[@]}" "$@" --set "Output/VTU/Interval=0" \
    --set "Output/Directory=$dir" > "$dir.log" 2>&1 \
    || { echo "quasi_newton.sh: $dir failed:" >&2; tail -3 "$dir.log" >&2; exit 1; }
}

error() { # run directory, reference directory: % of the largest probe motion
  /usr/bin/python3 - "$1/probes.csv" "$2/probes.csv" "$probe" <<'PY'
import csv, math, sys
def probe(name):
    return {round(float(r["time"]), 9): [float(r[k]) for k in ("ux", "uy", "uz")]
            for r in csv.DictReader(open(name)) if r["probe"] == sys.argv[3]}
run, ref = probe(sys.argv[1]), probe(sys.argv[2])
scale = max(math.dist(u, [0, 0, 0]) for u in ref.values())
print("%.1e" % (100 * max(math.dist(u, ref[t]) for t, u in run.items() if t in ref) / scale))
PY
}

row() { # label, directory
  printf '%-50s %9.1f %9.1f %8.1f %10s %7.2f\n' "$1" \
    "$(echo "1000 * $(value "$2" "step median")" | bc -l)" \
    "$(echo "1000 * $(value "$2" "step p95")" | bc -l)" \
    "$(value "$2" "wall total")" "$(error "$2" reference)" \
    "$(echo "$(value "$2" "step median") / $(value default "step median")" | bc -l)"
}

for name in box beam muscle; do
  [ "$which" = all ] || [ "$which" = "$name" ] || continue
  case $name in
    box) scene=("$top/parameters/box_3d_drag.prm" --set "Geometry/Cell type=simplex"
           --set "Geometry/Subdivisions=30, 8, 8" --set "Time integration/Time step=0.01"
           --set "Time integration/End time=0.3")
         probe=0 ;;
    beam) scene=("$top/parameters/sofa/beam_small.prm" --set "Linear solver/Type=direct"
           --set "Time integration/End time=0.5")
         probe=1 ;;
    muscle) scene=("$top/parameters/jeffrey_muscle.prm"
           --set "Time integration/Time step=0.03333333333333333"
           --set "Time integration/End time=0.5")
         probe=0 ;;
  esac
  be=(--set "Time integration/Integrator=backward Euler")
  qn=(--set "Time integration/Integrator=quasi-Newton backward Euler")
  run reference "${be[@]}" --set "Linear solver/Type=MUMPS" \
    --set "Newton solver/Relative residual tolerance=1e-12" \
    --set "Newton solver/Displacement tolerance=1e-12"
  run default "${be[@]}"
  run be-cg "${be[@]}" --set "Linear solver/Type=cg amg"
  run be-reuse "${be[@]}" --set "Newton solver/Jacobian reuse across steps=true"
  run qn "${qn[@]}" --set "Linear solver/Type=MUMPS"
  run qn-klu "${qn[@]}" --set "Linear solver/Type=KLU"
  run lie --set "Time integration/Integrator=linearly implicit Euler" \
    --set "Linear solver/Type=MUMPS"
  printf '\n%s\n%-50s %9s %9s %8s %10s %7s\n' "$name" run "median ms" "p95 ms" "run s" \
    "error %" "/ BE"
  row "backward Euler, defaults (MUMPS)" default
  row "backward Euler, cg amg" be-cg
  row "backward Euler, Jacobian reuse across steps" be-reuse
  row "quasi-Newton backward Euler, MUMPS" qn
  row "quasi-Newton backward Euler, KLU" qn-klu
  row "linearly implicit Euler, MUMPS" lie
done
