#!/bin/sh
# Jeffrey's active region (node freezing, report section 3): runs a scene
# with the damped central difference (default parameters/jeffrey_muscle.prm;
# PRM=parameters/active_region_slab.prm for a tool lifting a small patch of a
# large slab, where most of the body rests),
# first propagating every node (threshold 0, the reference), then with
# each threshold, and prints for each run
#   - the integrator's wall time summed over all steps (statistics.csv,
#     column step_seconds) and its ratio to the reference run's,
#   - the share of degrees of freedom propagated and cells evaluated,
#   - the error against the reference: the largest difference of the
#     displacement of probe PROBE (default 0; probes.csv) over the run relative to its
#     largest value, and the same for the tool force (tool_force.csv).
# Usage (from the repository top, after building):
#   sh parameters/studies/active_region.sh [path/to/tissuefem] [thresholds]
# Thresholds are in newtons (default "1e-4 1e-3 1e-2 1e-1 1 10"); END_TIME (s)
# shortens the run (default: the scene's 0.5 s). With CHECK=1 (the test
# studies/active_region) it fails unless every run completes (no blow-up at
# any threshold) and the probe error at the first threshold is below 1e-3.
set -e
exe=${1:-build/tissuefem}
thresholds=${2:-"1e-4 1e-3 1e-2 1e-1 1 10"}
prm=${PRM:-$(dirname "$0")/../jeffrey_muscle.prm}
end=${END_TIME:+"--set 'Time integration/End time=$END_TIME'"}
out=output-active-region-study
run() {
  mkdir -p "$out"
  if ! eval "\"$exe\" \"$prm\" --set 'Output/Directory=$out/$1' --set 'Output/VTU/Interval=0' \
    --set 'Time integration/Damped central difference/Active region threshold=$1' $end" \
    > "$out/log-$1" 2>&1; then
    touch "$out/failed"
    grep -i "failure\|error" "$out/log-$1" >&2 || true
  fi
  sed -n 's/^active region: on average \([^ ]*\) % of the degrees of freedom propagated and \([^ ]*\) %.*/\1 \2/p' "$out/log-$1"
}
seconds() { awk -F, 'NR > 1 { s += $10 } END { printf "%.3f", s }' "$out/$1/statistics.csv"; }
# Largest difference between two runs' columns (given as awk field lists),
# relative to the reference's largest magnitude.
difference() {
  awk -F, -v cols="$3" -v probe="$4" 'BEGIN { n = split(cols, c, " ") }
    FNR == 1 { next }
    probe != "" && $2 != probe { next }
    NR == FNR { for (i = 1; i <= n; ++i) ref[FNR, i] = $(c[i]); next }
    { d = 0; r = 0
      for (i = 1; i <= n; ++i) { d += ($(c[i]) - ref[FNR, i])^2; r += ref[FNR, i]^2 }
      if (sqrt(d) > dmax) dmax = sqrt(d); if (sqrt(r) > rmax) rmax = sqrt(r) }
    END { printf "%.2e", (rmax > 0 ? dmax / rmax : 0) }' "$1" "$2"
}
run 0 > /dev/null
t0=$(seconds 0)
printf '%-12s %12s %8s %12s %12s %14s %14s\n' "threshold" "steps (s)" "ratio" "dofs moved" "cells" "probe error" "force error"
printf '%-12s %12s %8s %12s %12s %14s %14s\n' "0 (full)" "$t0" "1.00" "100 %" "100 %" "-" "-"
first=
for th in $thresholds; do
  shares=$(run "$th")
  probe_error=$(difference "$out/0/probes.csv" "$out/$th/probes.csv" "6 7 8" "${PROBE:-0}")
  first=${first:-$probe_error}
  t=$(seconds "$th")
  printf '%-12s %12s %8s %10s %% %10s %% %14s %14s\n' "$th N" "$t" \
    "$(awk -v a="$t" -v b="$t0" 'BEGIN { printf "%.2f", a / b }')" \
    ${shares:-"- -"} \
    "$probe_error" \
    "$(difference "$out/0/tool_force.csv" "$out/$th/tool_force.csv" "6 7 8")"
done
status=0
if [ -n "$CHECK" ]; then
  if [ -e "$out/failed" ]; then
    echo "check failed: a run did not complete" >&2
    status=1
  fi
  if ! awk -v e="$first" 'BEGIN { exit !(e < 1e-3) }'; then
    echo "check failed: probe error $first at the first threshold is not below 1e-3" >&2
    status=1
  fi
fi
rm -rf "$out"
exit $status
