#!/bin/sh
# Stability map of the time integrators: for each integrator, Young's
# modulus E and mesh, the largest stable time step, found by bisection on
# the step, beside the critical step the explicit scheme prints.
#
# Scene: parameters/stability_map.prm, a 0.03 m block of s x s x s cubes
# (5 tetrahedra each; h = 0.03/s is the cube side), bottom fixed, released
# from a shear u_x = 0.3 z, St Venant-Kirchhoff, nu = 0.4, rho = 1000,
# gamma/m = 20 1/s. Every run takes a fixed number of steps of one size:
# no integrator may shrink its step (Radau IIA and ARKode with 'Adaptive
# step = false', 'Maximum step halvings = 0', the explicit scheme with
# 'Allow unstable step = true').
#
# A run at step dt counts as stable when
#   - it exits with status 0 (the explicit scheme stops with 3 when its
#     energy blows up; Newton or ARKode failures also give 3) within
#     STABILITY_TIMEOUT seconds,
#   - every row of statistics.csv has one substep and no rejected attempt
#     (Radau IIA retries a step whose Newton iteration fails with smaller
#     Runge-Kutta steps even in its fixed-step mode: that is not a step dt),
#   - the final probe displacement (top corner) and the 'distance from rest
#     shape' are finite and below the block size 0.03 m,
#   - stored plus kinetic energy never exceeds 1.5 times its value after
#     the first step (the block is released and damped: it only loses
#     energy).
# Bisection in log space between STABILITY_LOWER and STABILITY_UPPER
# (STABILITY_ITERATIONS halvings of the log interval): the upper bound is
# tried first, and a run stable there is reported as '>= upper bound'
# (backward Euler is, on this scene); a run unstable at the lower
# bound as '< lower bound'. The theoretical critical step is the one the
# damped central difference prints for the same scene (a one-step run).
#
# Writes, into the output directory:
#   stability.csv   integrator,E,subdivisions,h_element,
#                   critical_step_theory,largest_stable_step,
#                   smallest_unstable_step,runs,note
#                   (largest_stable_step is the cap with note '>= upper
#                   bound'; empty with note '< lower bound'; note also gives
#                   the failure message of the smallest unstable run)
#   stability.png   largest stable step against E, log-log, one panel per
#                   mesh, one colour per integrator, the theory dashed;
#                   open symbols on the dotted line: stable at the cap
#   runs/           the log and CSV files of the last run of each case
#
# Usage (from the repository top, after building):
#   sh parameters/studies/stability_map.sh [path/to/tissuefem] [output dir]
# Environment (defaults in brackets; the defaults take about 5 minutes on
# two cores; STABILITY_SUBDIVISIONS="2 4 8" about 25 more, mostly ARKode's
# implicit method, whose steps on 2560 tetrahedra take about a second):
#   STABILITY_E             Young's moduli, Pa ["1e3 1e4 1e5"]
#   STABILITY_SUBDIVISIONS  cubes per side ["2 4"]
#   STABILITY_INTEGRATORS   any of backward_euler central_difference
#                           radau_iia arkode_implicit arkode_explicit
#                           [all five]
#   STABILITY_LOWER, STABILITY_UPPER   bisection bounds, s [1e-5, 0.0333]
#                           (the upper one a visual frame: a larger step
#                           would not help an interactive simulation)
#   STABILITY_ITERATIONS    bisection steps [7]
#   STABILITY_STEPS         steps per run of the explicit methods [100]
#   STABILITY_IMPLICIT_STEPS  steps per run of the implicit ones [20]
#                           (they fail, if at all, in Newton's method in
#                           the first steps, where the deformation is
#                           largest)
#   STABILITY_TIMEOUT       wall-clock seconds per run [120]
#   STABILITY_THREADS       threads per run (tissuefem --threads) [all]
set -u
exe=${1:-build/tissuefem}
out=${2:-output-stability-map}
prm=$(dirname "$0")/../stability_map.prm
moduli=${STABILITY_E:-"1e3 1e4 1e5"}
subdivisions=${STABILITY_SUBDIVISIONS:-"2 4"}
integrators=${STABILITY_INTEGRATORS:-"backward_euler central_difference radau_iia arkode_implicit arkode_explicit"}
lower=${STABILITY_LOWER:-1e-5}
upper=${STABILITY_UPPER:-0.0333}
iterations=${STABILITY_ITERATIONS:-7}
explicit_steps=${STABILITY_STEPS:-100}
implicit_steps=${STABILITY_IMPLICIT_STEPS:-20}
time_limit=${STABILITY_TIMEOUT:-120}
threads=""
[ -n "${STABILITY_THREADS:-}" ] && threads="--threads $STABILITY_THREADS"
size=0.03

if [ ! -x "$exe" ]; then
  echo "stability_map.sh: no executable '$exe'" >&2
  exit 2
fi
mkdir -p "$out/runs" || exit 2
csv=$out/stability.csv
echo "integrator,E,subdivisions,h_element,critical_step_theory,largest_stable_step,smallest_unstable_step,runs,note" > "$csv"

label() {
  case $1 in
    backward_euler) echo "backward Euler";;
    central_difference) echo "damped central difference";;
    radau_iia) echo "Radau IIA";;
    arkode_implicit) echo "ARKode implicit";;
    arkode_explicit) echo "ARKode explicit";;
    *) echo "stability_map.sh: unknown integrator '$1'" >&2; return 1;;
  esac
}
for key in $integrators; do label "$key" > /dev/null || exit 2; done

# The scene's parameters for integrator $key, modulus $E, subdivisions $s.
scene() {
  case $key in
    backward_euler) set -- "Time integration/Integrator=backward Euler";;
    central_difference) set -- "Time integration/Integrator=damped central difference";;
    radau_iia) set -- "Time integration/Integrator=Radau IIA";;
    arkode_implicit) set -- "Time integration/Integrator=ARKode" "Time integration/ARKode/Method=implicit";;
    arkode_explicit) set -- "Time integration/Integrator=ARKode" "Time integration/ARKode/Method=explicit";;
  esac
  for a in "$@" "Materials/Young's modulus=$E" "Geometry/Subdivisions=$s, $s, $s"; do
    printf '%s\n' "$a"
  done
}

# run STEP NSTEPS DIR [--set ...]: one run of the scene; exit status of
# tissuefem (124 on timeout).
run() {
  step=$1; nsteps=$2; dir=$3; shift 3
  end=$(awk -v d="$step" -v n="$nsteps" 'BEGIN { printf "%.10g", d * n }')
  rm -rf "$dir"; mkdir -p "$dir"
  # Positional parameters: the scene's --set options, one per line.
  old_ifs=$IFS; IFS='
'
  set -- $(scene | sed 's/^/--set\
/')
  IFS=$old_ifs
  timeout "$time_limit" "$exe" "$prm" $threads "$@" \
    --set "Time integration/Time step=$step" --set "Time integration/End time=$end" \
    --set "Output/Directory=$dir" > "$dir/log.txt" 2>&1
}

# trial STEP: 0 if the scene is stable at STEP; sets $reason otherwise.
trial() {
  dir=$out/runs/$key-E$E-s$s
  case $key in
    central_difference|arkode_explicit) n=$explicit_steps;;
    *) n=$implicit_steps;;
  esac
  run "$1" "$n" "$dir"
  status=$?
  runs=$((runs + 1))
  if [ $status -eq 124 ]; then
    reason="timeout after $time_limit s"; return 1
  fi
  if [ $status -ne 0 ]; then
    reason=$(grep -m 1 -E 'error|failure' "$dir/log.txt" | sed 's/^tissuefem: //; s/,/;/g' | cut -c 1-160)
    reason="exit $status: ${reason:-no message}"; return 1
  fi
  reason=$(awk -F, -v L=$size '
    FNR == 1 { next }
    FILENAME ~ /statistics/ {
      if ($0 ~ /nan|inf/) { bad = "non-finite statistics" }
      if ($11 > 1 && !sub_) sub_ = "substeps " $11 " at t = " $2
      if ($6 > 0 && !rej) rej = "rejected attempts at t = " $2
      e = $13 + $14; if (first == "") first = e; if (e > emax) emax = e
      next }
    FILENAME ~ /probes/ { u = sqrt($6 * $6 + $7 * $7 + $8 * $8); line = $0 }
    END {
      if (bad) { print bad; exit }
      if (sub_) { print sub_; exit }
      if (rej) { print rej; exit }
      if (line ~ /nan|inf/ || !(u < L)) { printf "probe displacement %g\n", u; exit }
      if (emax > 1.5 * first) { printf "energy grew from %g to %g\n", first, emax; exit }
    }' "$dir/statistics.csv" "$dir/probes.csv")
  [ -n "$reason" ] && return 1
  distance=$(sed -n 's/^distance from rest shape \([^ ]*\) .*/\1/p' "$dir/log.txt")
  if ! awk -v d="$distance" -v L=$size 'BEGIN { exit !(d != "" && d !~ /nan|inf/ && d + 0 < L) }'; then
    reason="distance from rest shape $distance"; return 1
  fi
  return 0
}

for s in $subdivisions; do
  h=$(awk -v s="$s" -v L=$size 'BEGIN { printf "%.6g", L / s }')
  for E in $moduli; do
    # The explicit scheme's estimate for this scene (one step of 1e-9 s).
    key=central_difference
    run 1e-9 1 "$out/runs/theory-E$E-s$s"
    theory=$(sed -n 's/^damped central difference: estimated critical step \([^ ]*\) .*/\1/p' \
               "$out/runs/theory-E$E-s$s/log.txt")
    [ -z "$theory" ] && echo "stability_map.sh: E = $E, s = $s: no critical step printed" >&2
    for key in $integrators; do
      name=$(label "$key")
      runs=0; note=""; stable=""; unstable=""
      if trial "$upper"; then
        stable=$upper; note=">= upper bound"
      else
        unstable=$upper; note_upper=$reason
        if ! trial "$lower"; then
          unstable=$lower; note="< lower bound ($reason)"
        else
          stable=$lower; last_reason=$note_upper
          i=0
          while [ $i -lt "$iterations" ]; do
            mid=$(awk -v a="$stable" -v b="$unstable" 'BEGIN { printf "%.4g", sqrt(a * b) }')
            if trial "$mid"; then stable=$mid; else unstable=$mid; last_reason=$reason; fi
            i=$((i + 1))
          done
          note="unstable above: $last_reason"
        fi
      fi
      echo "$name,$E,$s,$h,$theory,$stable,$unstable,$runs,$note" >> "$csv"
      tail -n 1 "$csv"
    done
  done
done

if ! command -v gnuplot > /dev/null 2>&1; then
  echo "stability_map.sh: gnuplot not found, no chart" >&2
  exit 0
fi
colour() {
  case $1 in
    backward_euler) echo "lc rgb '#1f77b4'";;
    central_difference) echo "lc rgb '#d62728'";;
    radau_iia) echo "lc rgb '#2ca02c'";;
    arkode_implicit) echo "lc rgb '#9467bd'";;
    arkode_explicit) echo "lc rgb '#ff7f0e'";;
  esac
}
point() {  # filled point type; the open one is one less
  case $1 in
    backward_euler) echo 7;; central_difference) echo 5;; radau_iia) echo 9;;
    arkode_implicit) echo 11;; arkode_explicit) echo 13;;
  esac
}
# Per mesh and integrator a data file (E, largest stable step, 1 if stable
# at the cap); per mesh the theory (E, critical step).
count=0
for s in $subdivisions; do count=$((count + 1)); done
gp=$out/runs/stability.gp
{
  echo "set terminal pngcairo size $((430 * count + 100)),640 font ',10'"
  echo "set output '$out/stability.png'"
  echo "set multiplot layout 1,$count title 'largest stable fixed time step (bisection between $lower s and $upper s)' font ',11'"
  echo "set logscale xy"
  echo "set grid xtics ytics lc rgb '#cccccc'"
  echo "set xlabel \"Young's modulus E (Pa)\""
  echo "set format x '10^{%L}'; set format y '10^{%L}'"
  # Ranges from the data (and the cap).
  awk -F, -v cap="$upper" 'NR > 1 {
      if (e0 == "" || $2 + 0 < e0) e0 = $2 + 0; if ($2 + 0 > e1) e1 = $2 + 0
      if ($5 != "" && (y0 == "" || $5 + 0 < y0)) y0 = $5 + 0
      if ($6 != "" && (y0 == "" || $6 + 0 < y0)) y0 = $6 + 0 }
    END { if (y0 == "") y0 = cap / 10
          printf "set xrange [%g:%g]\nset yrange [%g:%g]\n", e0 / 2, e1 * 2, y0 / 4, cap * 3 }' "$csv"
  echo "set key bottom left font ',8' spacing 0.9 box opaque"
  for s in $subdivisions; do
    h=$(awk -v s="$s" -v L=$size 'BEGIN { printf "%.3g", 1000 * L / s }')
    echo "set title '$s x $s x $s cubes, h = $h mm ($((5 * s * s * s)) tetrahedra)'"
    if [ "$s" = "${subdivisions%% *}" ]; then echo "set ylabel 'time step (s)'"; else echo "unset ylabel"; fi
    awk -F, -v s="$s" 'NR > 1 && $3 == s && $5 != "" && !seen[$2]++ { print $2, $5 }' "$csv" \
      > "$out/runs/theory-s$s.dat"
    plots="$upper with lines dt 3 lc rgb '#777777' title 'cap (open symbols: stable at the cap)'"
    [ -s "$out/runs/theory-s$s.dat" ] &&
      plots="$plots, '$out/runs/theory-s$s.dat' using 1:2 with lines dt 2 lw 2 lc rgb 'black' title 'critical step (theory)'"
    for key in $integrators; do
      name=$(label "$key")
      awk -F, -v s="$s" -v n="$name" 'NR > 1 && $1 == n && $3 == s && $6 != "" { print $2, $6, ($9 ~ /^>=/) }' \
        "$csv" > "$out/runs/$key-s$s.dat"
      [ -s "$out/runs/$key-s$s.dat" ] || continue
      lc=$(colour "$key"); pt=$(point "$key")
      plots="$plots, '$out/runs/$key-s$s.dat' using 1:2 with lines lw 2 $lc notitle"
      plots="$plots, '$out/runs/$key-s$s.dat' using 1:(\$3 > 0.5 ? NaN : \$2) with points ps 1.2 $lc pt $pt notitle"
      plots="$plots, '$out/runs/$key-s$s.dat' using 1:(\$3 > 0.5 ? \$2 : NaN) with points ps 1.8 $lc pt $((pt - 1)) notitle"
      plots="$plots, keyentry with linespoints lw 2 ps 1.2 $lc pt $pt title '$name'"
    done
    echo "plot $plots"
  done
  echo "unset multiplot"
} > "$gp"
gnuplot "$gp" && echo "wrote $csv, $out/stability.png"
