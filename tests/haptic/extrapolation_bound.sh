#!/bin/bash
# The contact tool's haptic extrapolation between steps on
# parameters/muscle_palpation.prm (a ball pressed 8 mm into Jeffrey's
# muscle, held still from t = 0.2 to 0.3 while the tissue relaxes, then
# withdrawn): the largest error of the extrapolated force against the
# simulated one must stay below half the largest tool force. A device
# rendering an error of that size would feel a force that is not there;
# the secant stiffness once learnt from round-off motions of the still tool
# and extrapolated 1e11 force units (largest tool force 0.28).
# Usage: extrapolation_bound.sh TISSUEFEM SCENE WORKDIR
set -u
exe=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
"$exe" "$scene" --set "Output/Directory=out" --set "Output/VTU/Interval=0" \
  > run.log 2>&1 || { cat run.log; echo "FAILED: the run exited with $?"; exit 1; }
line=$(grep "extrapolation error" run.log) || { cat run.log; echo "FAILED: no extrapolation report"; exit 1; }
max=$(echo "$line" | sed -n 's/.*max \([^ ]*\) (force units; largest tool force \([^)]*\)).*/\1/p')
largest=$(echo "$line" | sed -n 's/.*largest tool force \([^)]*\)).*/\1/p')
[ -n "$max" ] && [ -n "$largest" ] || { echo "FAILED: cannot read '$line'"; exit 1; }
if awk -v m="$max" -v f="$largest" 'BEGIN { exit !(m == m + 0 && m < 0.5 * f) }'; then
  echo "haptic extrapolation error below half the largest tool force: ok"
else
  echo "FAILED: largest extrapolation error $max against a largest tool force $largest"
  exit 1
fi
