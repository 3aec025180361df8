#!/bin/bash
# Memory per process as the mesh is spread over processes ('Geometry/Mesh
# distribution', issue 32's "outgrowing one machine"): SOFA's large beam
# (parameters/sofa/beam_large.prm, 101,250 tetrahedra) over its first 0.2 s
# (5 steps) on one process, on two sharing the whole mesh, and on two that
# each hold their own cells and the layer around them; all in one run of
# this script, each solve converged (CG to a relative residual of 1e-8) so
# that the runs' answers can be compared.
#
# Per run: the peak resident memory of the largest process (MB, and kB per
# tetrahedron of the whole mesh), the memory the mesh and its numbering
# hold per process (MB, the solid's own account), the median step (ms),
# and the largest difference of the two probes' displacements from the
# one-process run over the 5 steps, relative to the largest probe
# displacement (the answers agree to the solver's tolerance).
#
# Usage (from the repository top, after building):
#   bash benchmarks/mesh_distribution.sh [path/to/tissuefem] [small|large]
# (OpenMPI as root also needs OMPI_ALLOW_RUN_AS_ROOT=1 and
# OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 in the environment.)
source "$(dirname "$0")/common.sh"
scene=$top/parameters/sofa/beam_${2:-large}.prm
launch="mpirun --oversubscribe"

run() { # directory, processes, distribution
  $launch -np "$2" "$exe" "$scene" --set "Time integration/End time=0.2" \
    --set "Linear solver/Relative tolerance=1e-8" \
    --set "Geometry/Mesh distribution=$3" --set "Output/VTU/Interval=0" \
    --set "Output/Directory=$1" > "$1.log" 2>&1 ||
    { tail -3 "$1.log" >&2; exit 1; }
}

difference() { # run directory, reference directory: relative, largest
  python3 - "$1/probes.csv" "$2/probes.csv" <<'EOF'
import csv, math, sys
def probes(name):
    return {(r["time"], r["probe"]): [float(r[k]) for k in ("ux", "uy", "uz")]
            for r in csv.DictReader(open(name))}
run, ref = probes(sys.argv[1]), probes(sys.argv[2])
assert run.keys() == ref.keys(), "the runs' probe times differ"
scale = max(math.dist(u, [0, 0, 0]) for u in ref.values())
print("%.1e" % (max(math.dist(run[k], ref[k]) for k in ref) / scale))
EOF
}

run np1 1 shared
run np2-shared 2 shared
run np2-distributed 2 distributed
cells=$(value np1 cells)
printf "%-34s %10s %8s %12s %10s %12s\n" "run ($cells tetrahedra)" \
  "peak MB" "kB/tet" "mesh+num MB" "median ms" "vs 1 process"
for dir in np1 np2-shared np2-distributed; do
  processes=$(value "$dir" processes)
  peak=$(value "$dir" "peak memory per process")
  mesh=$(python3 -c "print('%.1f' % (($(value "$dir" "memory mesh") + \
    $(value "$dir" "memory numbering")) / $processes))")
  median=$(python3 -c "print('%.1f' % (1e3 * $(value "$dir" "step median")))")
  per_tet=$(python3 -c "print('%.2f' % (1e3 * $peak / $cells))")
  printf "%-34s %10.1f %8s %12s %10s %12s\n" "$dir" "$peak" "$per_tet" \
    "$mesh" "$median" "$(difference "$dir" np1)"
done
echo "peak MB: the largest process's peak resident memory; kB/tet: that over"
echo "the whole mesh's tetrahedra (issue 32's target: at most 2 kB per tet at"
echo "101k); mesh+num MB: the mesh and its numbering per process"
