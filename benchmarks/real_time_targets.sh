#!/bin/bash
# Issue 32's step-time targets on the muscle and the 9,600-tetrahedra box,
# each figure beside its target, all measured in one run of this script
# (SOFA's beams: benchmarks/sofa_beams.sh; the peer: peer_fenics.py; the
# kernels against their floor: parameters/benchmark_assembly.prm and
# benchmark_floor.prm).
#
# Every figure is the wall time per step of the integrator (run.txt's
# 'step median' and 'step p95', statistics.csv's step_seconds), in ms:
# - the box (parameters/box_3d_drag.prm as simplices, 30 x 8 x 8 boxes of
#   6 tetrahedra, dt = 0.01 s, 20 steps), backward Euler with every default
#   (Newton to its tolerances: a converged step); target 20 ms;
# - Jeffrey's muscle (parameters/jeffrey_muscle.prm, 2,640 tetrahedra,
#   transversely isotropic St Venant-Kirchhoff), its explicit step (damped
#   central difference, dt = 5e-5 s, 1,000 steps); target 0.1 ms;
# - the corotational model against isotropic St Venant-Kirchhoff on the
#   muscle, explicit as above and with the linearly implicit Euler at
#   dt = 1/30 s (30 steps), as the ratio of the two medians and of the two
#   95th percentiles; target 1.5;
# - the muscle at the haptic rate: the linearly implicit Euler at dt = 2 ms
#   with KLU and one factorization per 10 steps (200 steps), made in the
#   step that needs it and, second, on a thread of its own ('Background
#   factorization'); target 2 ms for the median and for the 95th
#   percentile. Beside them, the probe's error against converged backward
#   Euler at the same step: the largest distance over the run between the
#   two probe displacements, relative to the reference's largest (%).
# The machine is shared: compare figures from one run of the script.
#
# Usage (from the repository top, after building in Release):
#   bash benchmarks/real_time_targets.sh [path/to/tissuefem]
source "$(dirname "$0")/common.sh"

muscle=$top/parameters/jeffrey_muscle.prm
box=$top/parameters/box_3d_drag.prm

run() { # directory, prm, settings...
  local dir=$1
  shift
  "$exe" "$@" --set "Output/VTU/Interval=0" --set "Output/Directory=$dir" \
    > "$dir.log" 2>&1 || { tail -3 "$dir.log" >&2; exit 1; }
}

ms() { # directory, run.txt key: ms
  awk -v s="$(value "$1" "$2")" 'BEGIN { printf "%.3f", 1000 * s }'
}

ratio() { # a, b: a / b
  awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'
}

line() { # label, figure, target
  printf '%-62s %10s %8s %8s\n' "$1" "$2" "$3" "$(ratio "$2" "$3")"
}

explicit=(--set "Time integration/End time=0.05")
implicit=(--set "Time integration/Integrator=linearly implicit Euler"
  --set "Time integration/Time step=0.0333333"
  --set "Time integration/End time=1")

run box "$box" --set "Geometry/Cell type=simplex" \
  --set "Geometry/Subdivisions=30, 8, 8" \
  --set "Time integration/Time step=0.01" \
  --set "Time integration/End time=0.2"
run explicit "$muscle" "${explicit[@]}"
run explicit-stvk "$muscle" "${explicit[@]}" \
  --set "Materials/Model=St Venant-Kirchhoff"
run explicit-corot "$muscle" "${explicit[@]}" \
  --set "Materials/Model=corotational linear elastic"
run implicit-stvk "$muscle" "${implicit[@]}" \
  --set "Materials/Model=St Venant-Kirchhoff"
run implicit-corot "$muscle" "${implicit[@]}" \
  --set "Materials/Model=corotational linear elastic"
haptic=(--set "Time integration/Time step=0.002"
  --set "Time integration/End time=0.4" --set "Linear solver/Type=KLU")
run haptic "$muscle" "${haptic[@]}" \
  --set "Time integration/Integrator=linearly implicit Euler" \
  --set "Time integration/Linearly implicit Euler/Factorization interval=10"
run haptic-background "$muscle" "${haptic[@]}" \
  --set "Time integration/Integrator=linearly implicit Euler" \
  --set "Time integration/Linearly implicit Euler/Factorization interval=10" \
  --set "Time integration/Linearly implicit Euler/Background factorization=true"
run haptic-reference "$muscle" "${haptic[@]}" \
  --set "Time integration/Integrator=backward Euler"

probe_error() { # run directory, reference directory: % of the largest motion
  python3 - "$1/probes.csv" "$2/probes.csv" <<'EOF'
import csv, math, sys
def probe(name):
    return {round(float(row["time"]), 9): [float(row[k]) for k in ("ux", "uy", "uz")]
            for row in csv.DictReader(open(name)) if row["probe"] == "0"}
run, ref = probe(sys.argv[1]), probe(sys.argv[2])
scale = max(math.dist(u, [0, 0, 0]) for u in ref.values())
# At the times both have (the reference may halve a step).
print("%.2f" % (100 * max(math.dist(run[t], ref[t]) for t in ref if t in run) / scale))
EOF
}

printf '%-62s %10s %8s %8s\n' "step time (ms) or ratio" figure target "/target"
line "box 9,600 tets, backward Euler, median ms" \
  "$(ms box "step median")" 20
line "box 9,600 tets, backward Euler, 95th percentile ms" \
  "$(ms box "step p95")" 20
line "muscle explicit step (TI StVK), median ms" \
  "$(ms explicit "step median")" 0.1
line "muscle explicit step (TI StVK), 95th percentile ms" \
  "$(ms explicit "step p95")" 0.1
line "corotational / StVK, explicit, medians" \
  "$(ratio "$(ms explicit-corot "step median")" \
    "$(ms explicit-stvk "step median")")" 1.5
line "corotational / StVK, explicit, 95th percentiles" \
  "$(ratio "$(ms explicit-corot "step p95")" \
    "$(ms explicit-stvk "step p95")")" 1.5
line "corotational / StVK, linearly implicit Euler 1/30 s, medians" \
  "$(ratio "$(ms implicit-corot "step median")" \
    "$(ms implicit-stvk "step median")")" 1.5
line "corotational / StVK, linearly implicit Euler 1/30 s, 95th perc." \
  "$(ratio "$(ms implicit-corot "step p95")" \
    "$(ms implicit-stvk "step p95")")" 1.5
line "muscle at dt = 2 ms (LIE, KLU, 1 factorization / 10), median ms" \
  "$(ms haptic "step median")" 2
line "muscle at dt = 2 ms (LIE, KLU, 1 factorization / 10), p95 ms" \
  "$(ms haptic "step p95")" 2
line "the same, factorized in the background, median ms" \
  "$(ms haptic-background "step median")" 2
line "the same, factorized in the background, p95 ms" \
  "$(ms haptic-background "step p95")" 2
printf '\nthe haptic runs against converged backward Euler at dt = 2 ms (probe error, %% of its largest displacement): 1 factorization / 10 %s, in the background %s\n' \
  "$(probe_error haptic haptic-reference)" \
  "$(probe_error haptic-background haptic-reference)"
printf '\nthe steps behind the ratios (ms, median and p95): explicit StVK %s %s, corotational %s %s; implicit StVK %s %s, corotational %s %s\n' \
  "$(ms explicit-stvk "step median")" "$(ms explicit-stvk "step p95")" \
  "$(ms explicit-corot "step median")" "$(ms explicit-corot "step p95")" \
  "$(ms implicit-stvk "step median")" "$(ms implicit-stvk "step p95")" \
  "$(ms implicit-corot "step median")" "$(ms implicit-corot "step p95")"
