#!/bin/bash
# A run on two processes that each hold only their own cells, checkpointed
# every 2 steps, restarted from its last checkpoint: the restarted run's
# summary must equal, bit for bit, the uninterrupted run's (restart/ shows
# the same on one process); restarting it with the mesh shared (the
# unknowns of each process in another order) must be refused, naming
# --restart, and leave the summary as it was.
#
#   restart.sh TISSUEFEM PRM WORKDIR
set -euo pipefail
tissuefem=$1 prm=$2 workdir=$3
rm -rf "$workdir" && mkdir -p "$workdir" && cd "$workdir"
settings=(--set "Output/Directory=run" --set "Output/Checkpoint interval=2"
  --set "Output/Summary file=summary.txt")
fail() { echo "FAIL: $*"; exit 1; }
mpirun -np 2 "$tissuefem" "$prm" "${settings[@]}" \
  --set "Geometry/Mesh distribution=distributed" > run.log 2>&1 ||
  fail "the run failed: $(tail -3 run.log)"
grep -q "^mesh distributed:" run.log || fail "the mesh was not distributed"
grep -q "^mesh distributed" run/checkpoint/checkpoint.txt ||
  fail "the checkpoint does not say its mesh was distributed"
cp summary.txt uninterrupted.txt
if mpirun -np 2 "$tissuefem" "$prm" "${settings[@]}" \
  --set "Geometry/Mesh distribution=shared" --restart run/checkpoint \
  > shared.log 2>&1; then
  fail "restarting on a shared mesh was not refused"
fi
grep -q "tissuefem: error: Parameter '--restart': the checkpoint was written on a distributed mesh" shared.log ||
  fail "the refusal does not name --restart: $(grep tissuefem: shared.log)"
cmp -s summary.txt uninterrupted.txt || fail "the refused restart changed the summary"
mpirun -np 2 "$tissuefem" "$prm" "${settings[@]}" \
  --set "Geometry/Mesh distribution=distributed" --restart run/checkpoint \
  > restart.log 2>&1 || fail "the restart failed: $(tail -3 restart.log)"
cmp summary.txt uninterrupted.txt || fail "the restarted run's summary differs"
echo "OK: restarted on a distributed mesh, the same summary; a shared restart refused"
