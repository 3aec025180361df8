#!/bin/sh
# Jeffrey's figure 2, measured: update rate against the number of
# tetrahedra. Runs parameters/jeffrey_timing.prm (a 10 x 10 x n slab of
# 0.01 m cubes, 5 tetrahedra each, bottom fixed, top shaken sideways,
# St Venant-Kirchhoff soft tissue) for each n and each time integrator:
#
#   backward Euler              fixed step DT
#   damped central difference   fixed step CFL x its critical step, which a
#                               first one-step run prints ('damped central
#                               difference: estimated critical step ...')
#   Radau IIA                   'Time step' DT, adaptive steps within it
#   ARKode implicit / explicit  'Time step' DT, adaptive steps within it
#
# An update is one 'Time step' of the run (one frame handed to a display
# or a haptic loop). From the run's last line, 'real time: ... median step
# M s', it computes updates per wall-clock second 1/M and the real-time
# factor dt/M (simulated seconds per wall-clock second; >= 1 keeps up with
# real time). Writes, into the output directory:
#
#   timing.csv        integrator,n,tets,unknowns,median_step_s,
#                     updates_per_s,simulated_time_per_step_s,
#                     real_time_factor,status
#   updates_per_s.png     log-log, updates per second against tetrahedra,
#                         30 Hz (visual) and 500 Hz (haptic) marked
#   real_time_factor.png  log-log, real-time factor against tetrahedra
#   runs/<integrator>-n<n>/   each run's statistics.csv and log.txt
#
# Wall-clock times depend on the machine and on what else runs on it: run
# it on an idle machine (and not beside a build).
#
# Usage (from the repository top, after building):
#   sh parameters/studies/jeffrey_timing.sh [path/to/tissuefem] [output dir]
# Environment (defaults in brackets):
#   TIMING_N            values of n ["2 4 8 16"]
#   TIMING_INTEGRATORS  any of backward_euler central_difference radau_iia
#                       arkode_implicit arkode_explicit [all five]
#   TIMING_DT           step of the implicit runs and ARKode, s [0.01]
#   TIMING_END          simulated time of every run, s [0.1]
#   TIMING_CFL          central difference step / critical step [0.8]
#   TIMING_THREADS      threads per run (tissuefem --threads) [all cores]
set -u
exe=${1:-build/tissuefem}
out=${2:-output-jeffrey-timing}
prm=$(dirname "$0")/../jeffrey_timing.prm
ns=${TIMING_N:-"2 4 8 16"}
integrators=${TIMING_INTEGRATORS:-"backward_euler central_difference radau_iia arkode_implicit arkode_explicit"}
dt=${TIMING_DT:-0.01}
end=${TIMING_END:-0.1}
cfl=${TIMING_CFL:-0.8}
threads=""
[ -n "${TIMING_THREADS:-}" ] && threads="--threads $TIMING_THREADS"

if [ ! -x "$exe" ]; then
  echo "jeffrey_timing.sh: no executable '$exe'" >&2
  exit 2
fi
mkdir -p "$out/runs" || exit 2
csv=$out/timing.csv
echo "integrator,n,tets,unknowns,median_step_s,updates_per_s,simulated_time_per_step_s,real_time_factor,status" > "$csv"

label() {
  case $1 in
    backward_euler) echo "backward Euler";;
    central_difference) echo "damped central difference";;
    radau_iia) echo "Radau IIA";;
    arkode_implicit) echo "ARKode implicit";;
    arkode_explicit) echo "ARKode explicit";;
    *) echo "jeffrey_timing.sh: unknown integrator '$1'" >&2; exit 2;;
  esac
}
for key in $integrators; do label "$key" > /dev/null || exit 2; done

failures=0
for n in $ns; do
  height=$(awk -v n="$n" 'BEGIN { printf "%.10g", 0.01 * n }')
  for key in $integrators; do
    name=$(label "$key")
    dir=$out/runs/$key-n$n
    mkdir -p "$dir"
    step=$dt
    case $key in
      backward_euler)
        set -- --set "Time integration/Integrator=backward Euler" \
               --set "Time integration/Backward Euler/Adaptive step=false";;
      central_difference)
        # One step of 1e-7 s only to print the critical step estimate.
        crit=$("$exe" "$prm" $threads --set "Geometry/Subdivisions=10, 10, $n" \
                 --set "Geometry/Upper corner=0.1, 0.1, $height" \
                 --set "Time integration/Integrator=damped central difference" \
                 --set "Time integration/Time step=1e-7" --set "Time integration/End time=1e-7" \
                 --set "Output/Directory=$dir" 2>&1 |
               sed -n 's/^damped central difference: estimated critical step \([^ ]*\) .*/\1/p')
        if [ -z "$crit" ]; then
          echo "jeffrey_timing.sh: n = $n: no critical step printed" >&2
          echo "$name,$n,,,,,,,no critical step" >> "$csv"
          failures=$((failures + 1))
          continue
        fi
        step=$(awk -v c="$crit" -v f="$cfl" 'BEGIN { printf "%.6g", f * c }')
        set -- --set "Time integration/Integrator=damped central difference";;
      radau_iia)
        set -- --set "Time integration/Integrator=Radau IIA";;
      arkode_implicit)
        set -- --set "Time integration/Integrator=ARKode" --set "Time integration/ARKode/Method=implicit";;
      arkode_explicit)
        set -- --set "Time integration/Integrator=ARKode" --set "Time integration/ARKode/Method=explicit";;
    esac
    "$exe" "$prm" $threads "$@" \
      --set "Geometry/Subdivisions=10, 10, $n" --set "Geometry/Upper corner=0.1, 0.1, $height" \
      --set "Time integration/Time step=$step" --set "Time integration/End time=$end" \
      --set "Output/Directory=$dir" > "$dir/log.txt" 2>&1
    status=$?
    cells=$(sed -n 's/.*elasticity, \([0-9]*\) cells, \([0-9]*\) unknowns.*/\1/p' "$dir/log.txt")
    unknowns=$(sed -n 's/.*elasticity, \([0-9]*\) cells, \([0-9]*\) unknowns.*/\2/p' "$dir/log.txt")
    median=$(sed -n 's/^real time: .*median step \([^ ]*\) s.*/\1/p' "$dir/log.txt")
    if [ $status -ne 0 ] || [ -z "$median" ]; then
      echo "jeffrey_timing.sh: $name, n = $n: exit status $status:" >&2
      grep -i -E 'error|fail' "$dir/log.txt" | head -3 >&2
      echo "$name,$n,$cells,$unknowns,,,$step,,exit $status" >> "$csv"
      failures=$((failures + 1))
      continue
    fi
    awk -v name="$name" -v n="$n" -v c="$cells" -v u="$unknowns" -v m="$median" -v dt="$step" \
      'BEGIN { printf "%s,%s,%s,%s,%s,%.4g,%s,%.4g,ok\n", name, n, c, u, m, 1 / m, dt, dt / m }' >> "$csv"
    tail -n 1 "$csv"
  done
done

if ! command -v gnuplot > /dev/null 2>&1; then
  echo "jeffrey_timing.sh: gnuplot not found, no charts" >&2
  exit $((failures > 0))
fi
# One data file per integrator (tets, updates per second, real-time
# factor); a fixed colour and point type per integrator in both charts.
style() {
  case $1 in
    backward_euler) echo "lc rgb '#1f77b4' pt 7";;
    central_difference) echo "lc rgb '#d62728' pt 5";;
    radau_iia) echo "lc rgb '#2ca02c' pt 9";;
    arkode_implicit) echo "lc rgb '#9467bd' pt 11";;
    arkode_explicit) echo "lc rgb '#ff7f0e' pt 13";;
  esac
}
plots_u=""; plots_r=""
for key in $integrators; do
  name=$(label "$key")
  awk -F, -v name="$name" '$1 == name && $9 == "ok" { print $3, $6, $8 }' "$csv" > "$out/runs/$key.dat"
  [ -s "$out/runs/$key.dat" ] || continue
  plots_u="$plots_u${plots_u:+, }'$out/runs/$key.dat' using 1:2 with linespoints lw 2 ps 1.3 $(style "$key") title '$name'"
  plots_r="$plots_r${plots_r:+, }'$out/runs/$key.dat' using 1:3 with linespoints lw 2 ps 1.3 $(style "$key") title '$name'"
done
if [ -z "$plots_u" ]; then
  echo "jeffrey_timing.sh: no successful run, no charts" >&2
  exit 1
fi
# Axis ranges that hold the data and the reference lines (30 and 500 Hz; 1).
set -- $(awk -F, '$9 == "ok" {
    if (x0 == "" || $3 + 0 < x0) x0 = $3 + 0; if ($3 + 0 > x1) x1 = $3 + 0
    if (u0 == "" || $6 + 0 < u0) u0 = $6 + 0; if ($6 + 0 > u1) u1 = $6 + 0
    if (r0 == "" || $8 + 0 < r0) r0 = $8 + 0; if ($8 + 0 > r1) r1 = $8 + 0 }
  END { if (u0 > 30) u0 = 30; if (u1 < 500) u1 = 500; if (r0 > 1) r0 = 1; if (r1 < 1) r1 = 1
        printf "%g %g %g %g %g %g\n", x0 / 1.5, x1 * 1.5, u0 / 3, u1 * 3, r0 / 3, r1 * 3 }' "$csv")
# x tics at the measured numbers of tetrahedra.
xtics=$(awk -F, '$9 == "ok" && !seen[$3]++ { printf "%s%s", sep, $3; sep = ", " }' "$csv")
gnuplot <<EOF
set terminal pngcairo size 900,650 font ',11'
set logscale xy
set grid xtics ytics lc rgb '#cccccc'
set key outside below horizontal maxrows 2
set xlabel 'tetrahedra (10 x 10 x n cubes of 0.01 m, 5 tetrahedra each)'
set xrange [$1:$2]
set xtics ($xtics)
set bmargin 7
set format y '10^{%L}'

set output '$out/updates_per_s.png'
set title "updates per wall-clock second (update = one 'Time step'; median step time)"
set ylabel 'updates per second'
set yrange [$3:$4]
set arrow 1 from graph 0, first 500 to graph 1, first 500 nohead dt 2 lw 1.5 lc rgb '#555555'
set arrow 2 from graph 0, first 30 to graph 1, first 30 nohead dt 2 lw 1.5 lc rgb '#555555'
set label 1 '500 Hz (haptic)' at graph 0.98, first 500 right offset 0, 0.7
set label 2 '30 Hz (visual)' at graph 0.98, first 30 right offset 0, 0.7
plot $plots_u

set output '$out/real_time_factor.png'
set title 'real-time factor: simulated time per wall-clock time (dt / median step time)'
set ylabel 'simulated s per wall-clock s'
set yrange [$5:$6]
unset arrow 2; unset label 2
set arrow 1 from graph 0, first 1 to graph 1, first 1 nohead dt 2 lw 1.5 lc rgb '#555555'
set label 1 'real time (factor 1)' at graph 0.98, first 1 right offset 0, 0.7
plot $plots_r
EOF
echo "wrote $csv, $out/updates_per_s.png, $out/real_time_factor.png"
[ $failures -eq 0 ]
