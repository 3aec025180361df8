#!/bin/bash
# Hertz indentation (parameters/hertz_indentation.prm): the error of the
# contact force and of the contact radius against Hertz's closed form, over
# meshes, elements and contact methods, against the wall time of the run.
#
#   closed form   F = 4/3 E / (1 - nu^2) R^(1/2) d^(3/2) = 3.663e-4 N and
#                 a = (R d)^(1/2) = 1 mm at full depth (the scene models a
#                 quarter: its force and area are multiplied by 4)
#   measured      F_h: the probe's force (contact.csv, z component, times
#                 4); a_h = (4 A / pi)^(1/2), A the reference area whose
#                 face quadrature points carry a pressure (contact.csv)
#   meshes        the scene's graded box with 'Subdivisions' n = 8 to 32
#                 per direction at the same 'Grading' (25): every cell
#                 shrinks as 1 / n, the smallest (at the contact) from 1 a
#                 to a / 4; hexahedra (Q1) and the same boxes split into
#                 tetrahedra (P1); Q1 refined adaptively (Kelly) from
#                 n = 8, two load steps then six re-solves at full depth,
#                 each after refining the 15 % of cells with the largest
#                 indicator; and, where Gmsh is installed (Debian's gmsh),
#                 P1 on tetrahedra graded by Gmsh (hertz_quarter.geo: edge
#                 length h0 within 2 a of the contact, growing by g per
#                 unit of distance beyond), for the pairs h0:g in
#                 GMSH_MESHES (deal.II 9.4 cannot refine tetrahedra
#                 locally)
#   methods       the penalty (its default factor) and the augmented
#                 Lagrangian (gaps within 1e-3 d)
#   wall time     the whole run, start-up and output included (s), with
#                 the linear solver 'cg amg' for every run; for the
#                 adaptive runs one row per mesh at full depth, the wall
#                 time of the steps up to it plus the whole run's other
#                 time (start-up, mesh changes); no VTU output
#
# Writes DIR/hertz.csv and, with gnuplot, DIR/hertz_force_error.png (force
# error against wall time, log-log) and DIR/hertz_radius_error.png. What it
# showed on the development machine is in doc/studies.md.
#
# Usage (from the repository top, after building):
#   bash parameters/studies/hertz.sh [path/to/tissuefem] [DIR]
#   SIZES="8 12" METHODS=penalty bash parameters/studies/hertz.sh  (a quick look)
#   GMSH_MESHES="" ...  (no Gmsh meshes)
set -euo pipefail
exe=$(realpath "${1:-build/tissuefem}")
out=$(realpath -m "${2:-hertz-study}")
prm=$(realpath "$(dirname "$0")/../hertz_indentation.prm")
mkdir -p "$out/runs"
read -r -a sizes <<< "${SIZES-8 12 16 24 32}"
read -r -a methods <<< "${METHODS:-penalty augmented_Lagrangian}"
read -r -a gmsh_meshes <<< "${GMSH_MESHES-1.25e-4:0.2 1.25e-4:0.1 8.33e-5:0.1 6.25e-5:0.1}"
geo=$(realpath "$(dirname "$0")/hertz_quarter.geo")
# RADIUS=0.01: a sphere of 10 mm pressed 0.1 mm (a / R = 0.1 instead of
# the scene's 0.025, the same contact radius a = 1 mm), to see how much of
# the error is Hertz's own (his theory is the limit a / R -> 0).
radius=${RADIUS:-0.04}
depth=$(awk -v r="$radius" 'BEGIN { printf "%.10g", 1e-6 / r }')
csv=$out/hertz.csv
echo "element,mesh,method,cells,unknowns,force (N),force error,radius (m),radius error,penetration over d,wall (s)" > "$csv"

# run ELEMENT MESH METHOD ARGS...: one run, one row of the CSV.
run() {
  local element=$1 mesh=$2 method=$3
  shift 3
  local dir=$out/runs/$element-$mesh-$method
  local args=(--set "Output/Directory=$dir" --set "Output/VTU/Interval=0" --set "Linear solver/Type=cg amg"
              --set "Contact/Method=${method//_/ }" --set "Contact/Gap tolerance=$(awk -v d="$depth" 'BEGIN { print 1e-3 * d }')"
              --set "Contact/Obstacle 1/sphere/Radius=$radius" --set "Contact/Obstacle 1/sphere/Centre=0, 0, $radius"
              --set "Contact/Obstacle 1/Motion=0; 0; -$depth*min(t, 1)")
  [ "$element" = P1 ] && args+=(--set "Geometry/Cell type=simplex")
  local start end
  start=$(date +%s.%N)
  if ! "$exe" "$prm" "${args[@]}" "$@" > "$dir.log" 2>&1; then
    echo "$element,$mesh,$method,,,,,,,,failed (see $dir.log)" | tee -a "$csv"
    return
  fi
  end=$(date +%s.%N)
  # Per step: the mesh it was solved on (the first line's cells and
  # unknowns, then each "mesh adapted" line's) and its wall time
  # (statistics.csv, step_seconds); the run's start-up and output, the
  # whole run's wall time less its steps', count toward every row.
  grep -o '[0-9]* cells, [0-9]* unknowns' "$dir.log" | tr -d ',' | awk '{ print $1, $3 }' > "$dir.meshes"
  awk -F, 'NR > 1 { print $10 }' "$dir/statistics.csv" > "$dir.steps"
  # Rows of contact.csv (time, obstacle, FX, FY, FZ, penetration, area,
  # min and max pressure) at full depth: the last of a run on one mesh,
  # every one (one per mesh) of an adaptive run.
  awk -F, 'NR > 1 && $1 >= 1 - 1e-9' "$dir/contact.csv" \
    | { [ "$mesh" = adaptive ] && cat || tail -n 1; } \
    | awk -F, -v e="$element" -v m="$mesh" -v me="$method" -v s="$start" -v t="$end" \
        -v R="$radius" -v d="$depth" -v meshes="$dir.meshes" -v steps="$dir.steps" '
      BEGIN {
        while ((getline line < meshes) > 0) { split(line, f, " "); cells[++nm] = f[1]; unknowns[nm] = f[2] }
        while ((getline line < steps) > 0) { seconds[++ns] = line; total += line }
        overhead = t - s - total
        E = 1e4; nu = 0.3
        F = 4 / 3 * E / (1 - nu * nu) * sqrt(R) * d ^ 1.5; a = sqrt(R * d)
      }
      {
        # The step of this row: its time over the step size of the rows
        # (the run has no rejected steps when the rows are evenly spaced).
        k = (m == "adaptive") ? int($1 / 0.5 + 0.5) : ns
        used = overhead; for (i = 1; i <= k; ++i) used += seconds[i]
        j = k; if (j > nm) j = nm
        Fh = -4 * $5; ah = sqrt(4 * $7 / 3.141592653589793)
        printf "%s,%s,%s,%s,%s,%.5g,%.4f,%.5g,%.4f,%.2g,%.1f\n", e, m, me, cells[j],
          unknowns[j], Fh, Fh / F - 1, ah, ah / a - 1, $6 / d, used }' | tee -a "$csv"
}

for element in Q1 P1; do
  for method in "${methods[@]}"; do
    for n in "${sizes[@]}"; do
      run "$element" "n$n" "$method" --set "Geometry/Subdivisions=$n, $n, $n"
    done
  done
done
if [ ${#gmsh_meshes[@]} -gt 0 ] && ! command -v gmsh > /dev/null 2>&1; then
  echo "hertz.sh: gmsh not found (apt-get install gmsh), no Gmsh-graded tetrahedra" >&2
  gmsh_meshes=()
fi
for pair in "${gmsh_meshes[@]}"; do
  h0=${pair%:*} g=${pair#*:}
  mesh=$out/runs/gmsh-$h0-$g.msh
  gmsh -3 -format msh2 -setnumber h0 "$h0" -setnumber g "$g" "$geo" -o "$mesh" > "$mesh.log" 2>&1 ||
    { echo "hertz.sh: gmsh failed (see $mesh.log)" >&2; continue; }
  for method in "${methods[@]}"; do
    run P1 "gmsh-h0=$h0-g=$g" "$method" --set "Geometry/Source=file" --set "Geometry/Mesh file=$mesh"
  done
done
for method in "${methods[@]}"; do
  run Q1 adaptive "$method" --set "Geometry/Subdivisions=8, 8, 8" \
    --set "Time integration/Time step=0.5" --set "Time integration/End time=4" \
    --set "Mesh refinement/Indicator=Kelly" --set "Mesh refinement/Refine fraction=0.15" \
    --set "Mesh refinement/Coarsen fraction=0" --set "Mesh refinement/Maximum levels=6"
done

if ! command -v gnuplot > /dev/null 2>&1; then
  echo "hertz.sh: gnuplot not found, no charts (the table is $csv)" >&2
  exit 0
fi
# One data file per element and method: wall time, |force error|, |radius
# error| (in %), and the mesh label.
plots_f=""; plots_a=""
for series in "Q1 n penalty" "Q1 n augmented_Lagrangian" "P1 n penalty" "P1 n augmented_Lagrangian" \
              "Q1 adaptive penalty" "Q1 adaptive augmented_Lagrangian" \
              "P1 gmsh penalty" "P1 gmsh augmented_Lagrangian"; do
  read -r element mesh method <<< "$series"
  file=$out/runs/$element-$mesh-$method.dat
  awk -F, -v e="$element" -v m="$mesh" -v me="$method" \
    '$1 == e && index($2, m) == 1 && $3 == me && $11 != "" && $11 !~ /failed/ {
       f = $7 < 0 ? -$7 : $7; r = $9 < 0 ? -$9 : $9; print $11, 100 * f, 100 * r, $2 }' "$csv" > "$file"
  [ -s "$file" ] || continue
  case $mesh in
    n) title="$element graded boxes, ${method//_/ }" ;;
    gmsh) title="$element Gmsh-graded, ${method//_/ }" ;;
    *) title="$element $mesh, ${method//_/ }" ;;
  esac
  plots_f="$plots_f${plots_f:+, }'$file' using 1:2 with linespoints lw 2 ps 1.3 title '$title'"
  plots_a="$plots_a${plots_a:+, }'$file' using 1:3 with linespoints lw 2 ps 1.3 title '$title'"
done
gnuplot <<GNUPLOT
set terminal pngcairo size 900,650 font ',11'
set logscale xy
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key outside below maxrows 4
set xlabel 'wall time of the run (s, 2 cores)'
set output '$out/hertz_force_error.png'
set title 'Hertz indentation: force error |F_h / F - 1| against wall time'
set ylabel 'force error (%)'
set arrow 1 from graph 0, first 2 to graph 1, first 2 nohead dt 2 lc rgb '#555555'
set label 1 '2 % (target)' at graph 0.98, first 2 right offset 0, 0.7
plot $plots_f
set output '$out/hertz_radius_error.png'
set title 'Hertz indentation: contact radius error |a_h / a - 1| against wall time'
set ylabel 'contact radius error (%)'
set arrow 1 from graph 0, first 5 to graph 1, first 5 nohead dt 2 lc rgb '#555555'
set label 1 '5 % (target)' at graph 0.98, first 5 right offset 0, 0.7
plot $plots_a
GNUPLOT
echo "wrote $csv, $out/hertz_force_error.png, $out/hertz_radius_error.png"
