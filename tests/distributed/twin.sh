#!/bin/bash
# Runs a prm test's scene on two processes that each hold only their own
# cells and the layer around them (Geometry/Mesh distribution =
# distributed) and compares its summary, to the tolerances deal.II's tests
# use, with
# - EXPECTED, the stored output of the same scene on two processes sharing
#   the whole mesh (from the scene's closed form or its own record), or
# - if EXPECTED is 'shared', the summary of that run made here, when the
#   extra settings (further arguments, each NAME=VALUE for --set) refine a
#   scene too small to be cut.
#
#   twin.sh TISSUEFEM PRM EXPECTED WORKDIR [NAME=VALUE ...]
set -euo pipefail
tissuefem=$1 prm=$2 expected=$3 workdir=$4
shift 4
sets=()
for s in "$@"; do sets+=(--set "$s"); done
rm -rf "$workdir" && mkdir -p "$workdir" && cd "$workdir"
run() { # run DIRECTORY DISTRIBUTION
  mkdir -p "$1"
  (cd "$1" && mpirun -np 2 "$tissuefem" "$prm" "${sets[@]}" \
    --set "Geometry/Mesh distribution=$2" > screen.txt 2>&1) || {
    cat "$1/screen.txt"
    echo "FAIL: the run on a $2 mesh failed"
    exit 1
  }
}
if [ "$expected" = shared ]; then
  run shared shared
  expected=$PWD/shared/output
fi
run distributed distributed
# The run must say the mesh was cut, and no process may hold all of it.
line=$(grep "^mesh distributed:" distributed/screen.txt) || {
  cat distributed/screen.txt
  echo "FAIL: the mesh was not distributed"
  exit 1
}
echo "$line"
held=$(sed -E 's/.*holds at most ([0-9]+) of ([0-9]+) cells.*/\1 \2/' <<<"$line")
read -r most all <<<"$held"
if ! [[ "$most" =~ ^[0-9]+$ && "$all" =~ ^[0-9]+$ ]]; then
  echo "FAIL: cannot read the cells held from: $line"
  exit 1
fi
if [ "$most" -ge "$all" ]; then
  echo "FAIL: a process holds all $all cells"
  exit 1
fi
numdiff -q -a 1e-6 -r 1e-8 -s ' \t\n:<>=,;' distributed/output "$expected" || {
  diff distributed/output "$expected" | head -20
  echo "FAIL: the summary differs from $expected"
  exit 1
}
echo "OK: the same output as on a shared mesh"
