#!/bin/bash
# Step time against mesh size (Jeffrey's figure 2 carried to scale, issue
# 32): SOFA's small benchmark beam (parameters/sofa/beam_small.prm:
# corotational elasticity, gravity, Rayleigh damping 0.1/0.1, dt 0.01)
# meshed as 4m x m x m boxes of 6 tetrahedra each (24 m^3 tets, m = 4 to
# 26: 1,536 to 421,824 tets), for the linearly implicit Euler, backward
# Euler and the quasi-Newton backward Euler, each with MUMPS and with CG +
# AMG (MUMPS up to 65,856 tets: beyond, backward Euler's factorizations
# take minutes a step), and for the damped central difference (explicit, no
# linear solver: solver 'none'; without the scene's Rayleigh damping, which
# only the implicit integrators take, at dt = 1e-4 s, below the critical
# step of the finest mesh), on 1 thread, 2 threads and 2 MPI processes of
# 1 thread.
#
# Each implicit run takes 'steps' steps (default 4) from rest, each explicit
# run 20 steps. Per run, in the CSV:
#   tets, integrator, solver, config (t1, t2, np2),
#   step_median_ms    median wall time of the integrator's step,
#   step_p95_ms       its 95th percentile (the largest of few steps),
#   assembly_ms       median per step of residual and Jacobian assembly,
#   solve_ms          median per step of the linear solves (AMG rebuilds
#                     and numeric factorizations included),
#   setup_s           symbolic factorizations or AMG builds over the run (s),
#   newton_per_step   Newton iterations per step (1 for the linearly
#                     implicit Euler),
#   wall_total_s      the whole run (mesh, set-up, steps, output),
#   peak_kB_per_tet   peak resident memory over all processes / tets.
# Charts (gnuplot, if installed): scaling_step.png (median step against tets,
# log-log, every run) and scaling_split.png (where the step goes on 2
# threads: step, assembly, linear solve and the set-up within it, per step,
# for the linearly implicit Euler and backward Euler with CG + AMG and
# backward Euler with MUMPS).
#
# Usage (from the repository top, after building; about 45 minutes for all):
#   bash benchmarks/scaling.sh [path/to/tissuefem] [output directory]
#     [largest m (default 26)] [steps (default 4)]
# doc/figures/scaling.csv and the two charts there were made so.
set -euo pipefail
exe=$(realpath "${1:-build/tissuefem}")
out=$(realpath -m "${2:-doc/figures}")
largest=${3:-26}
steps=${4:-4}
top=$(realpath "$(dirname "$0")/..")
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
csv="$out/scaling.csv"
echo "tets,integrator,solver,config,step_median_ms,step_p95_ms,assembly_ms,solve_ms,setup_s,newton_per_step,wall_total_s,peak_kB_per_tet" > "$csv"

summarize() { # directory, log, tets, integrator, solver, config
  /usr/bin/python3 - "$@" <<'PY'
import csv, re, statistics, sys
d, log, tets, integrator, solver, config = sys.argv[1:]
rows = list(csv.DictReader(open(d + "/statistics.csv")))
def median(key):
    return statistics.median(float(r[key]) for r in rows)
run = {}
for line in open(d + "/run.txt"):
    m = re.match(r"(.+?) = (\S+)", line)
    if m:
        run[m.group(1)] = float(m.group(2))
setup = re.search(r"AMG builds \(([0-9.e+-]+) s\)", open(log).read())
steps = [float(r["step_seconds"]) for r in rows]
newton = sum(int(r["newton_iterations"]) for r in rows) / len(rows)
print(",".join([tets, integrator, solver, config,
                "%.2f" % (1e3 * median("step_seconds")),
                "%.2f" % (1e3 * sorted(steps)[min(len(steps) - 1, int(0.95 * len(steps)))]),
                "%.2f" % (1e3 * median("assembly_seconds")),
                "%.2f" % (1e3 * median("solve_seconds")),
                "%.3f" % float(setup.group(1)) if setup else "nan",
                "%.2f" % newton, "%.2f" % run["wall total"],
                "%.2f" % (1e3 * run["peak memory"] / float(tets))]))
PY
}

for m in 4 6 8 11 14 18 22 26; do
  [ "$m" -le "$largest" ] || continue
  tets=$((24 * m * m * m))
  for integrator in "linearly implicit Euler" "backward Euler" \
    "quasi-Newton backward Euler" "damped central difference"; do
    explicit=$([ "$integrator" = "damped central difference" ] && echo 1 || echo 0)
    for solver in "cg amg" MUMPS; do
      [ "$solver" = MUMPS ] && [ "$tets" -gt 70000 ] && continue
      [ "$explicit" = 1 ] && [ "$solver" = MUMPS ] && continue
      settings=(--set "Time integration/End time=$(echo "0.01 * $steps" | bc -l)"
        --set "Linear solver/Type=$solver")
      [ "$explicit" = 1 ] && settings=(--set "Time integration/Time step=1e-4"
        --set "Time integration/End time=2e-3"
        --set "Time integration/Rayleigh mass damping=0"
        --set "Time integration/Rayleigh stiffness damping=0")
      label=$([ "$explicit" = 1 ] && echo none || echo "$solver")
      for config in t1 t2 np2; do
        dir="$work/run"
        rm -rf "$dir"
        launch=("$exe" --threads 1)
        [ "$config" = t2 ] && launch=("$exe" --threads 2)
        [ "$config" = np2 ] && launch=(mpirun --oversubscribe -np 2 "$exe" --threads 1)
        if ! "${launch[@]}" "$top/parameters/sofa/beam_small.prm" \
          --set "Geometry/Subdivisions=$((4 * m)), $m, $m" \
          --set "Time integration/Integrator=$integrator" "${settings[@]}" \
          --set "Output/VTU/Interval=0" --set "Output/Directory=$dir" \
          > "$work/log" 2>&1; then
          echo "scaling.sh: $tets tets, $integrator, $label, $config failed:" >&2
          tail -3 "$work/log" >&2
          continue
        fi
        summarize "$dir" "$work/log" "$tets" "$integrator" "$label" "$config" | tee -a "$csv"
      done
    done
  done
done

if ! command -v gnuplot > /dev/null 2>&1; then
  echo "scaling.sh: gnuplot not found, no charts" >&2
  exit 0
fi
# The split chart's panels: integrator and solver as the CSV names them.
panels=""
for run in "linearly implicit Euler,cg amg" "backward Euler,cg amg" \
  "backward Euler,MUMPS"; do
  panels+="set title '${run/,/, }'
plot '< grep \"^[0-9]*,$run,t2,\" $csv' using 1:5 with linespoints title 'step', \\
  '' using 1:7 with linespoints title 'assembly', \\
  '' using 1:8 with linespoints title 'linear solve', \\
  '' using 1:(\$9 * 1000 / $steps) with linespoints title 'set-up'
"
done
# One data file per curve, for gnuplot.
/usr/bin/python3 - "$csv" "$work" <<'PY'
import csv, sys
curves = {}
for r in csv.DictReader(open(sys.argv[1])):
    key = "%s, %s, %s" % (r["integrator"], r["solver"], r["config"])
    curves.setdefault(key, []).append(r)
with open(sys.argv[2] + "/curves.txt", "w") as f:
    for key, rows in curves.items():
        f.write('"%s"\n' % key)
        for r in rows:
            f.write("%s %s %s %s\n" % (r["tets"], r["step_median_ms"],
                                        r["assembly_ms"], r["solve_ms"]))
        f.write("\n\n")
PY
gnuplot <<GP
set terminal pngcairo size 1000,700 font ',10'
set datafile separator whitespace
set logscale xy
set grid
set key outside right top
set xlabel 'tetrahedra'
set ylabel 'wall time per step (ms, median)'
set title "SOFA's beam, 4m x m x m boxes of 6 tets: step time against size (2 cores)"
set output '$out/scaling_step.png'
plot for [i=0:20] '$work/curves.txt' index i using 1:2 with linespoints title columnheader(1), \
  33.3 with lines dt 2 lc rgb 'black' title 'visual frame, 1/30 s'
set terminal pngcairo size 1500,520 font ',10'
set output '$out/scaling_split.png'
set datafile separator ','
set key inside left top
set ylabel 'wall time per step (ms; set-up: its share of the run, per step)'
set multiplot layout 1,3 title "Where the step goes, 2 threads (set-up: AMG builds or symbolic factorizations, within the linear solve)"
$panels
unset multiplot
GP
echo "wrote $csv, $out/scaling_step.png, $out/scaling_split.png"
