#!/bin/sh
# Jeffrey's figure 4 claim, measured: runs parameters/jeffrey_block.prm for
# each material and formulation and prints the largest node distance from
# the rest shape after settling (after the best rigid fit; metres).
# Usage (from the repository top, after building):
#   sh parameters/studies/jeffrey_block.sh [path/to/tissuefem]
set -e
exe=${1:-build/tissuefem}
prm=$(dirname "$0")/../jeffrey_block.prm
printf '%-45s %-13s %s\n' "material" "formulation" "distance from rest shape at t = 1.5 s (m)"
for case in "linear elastic|displacement" \
            "St Venant-Kirchhoff|displacement" "St Venant-Kirchhoff|edge length" \
            "transversely isotropic St Venant-Kirchhoff|displacement" \
            "transversely isotropic St Venant-Kirchhoff|edge length" \
            "robust neo-Hookean|displacement"; do
  model=${case%|*}; form=${case#*|}
  d=$("$exe" "$prm" --set "Materials/Model=$model" --set "Materials/Formulation=$form" \
        --set "Output/Directory=output-jeffrey-block-study" --set "Output/VTU/Interval=0" |
      sed -n 's/^distance from rest shape \([^ ]*\) .*/\1/p')
  printf '%-45s %-13s %s\n' "$model" "$form" "$d"
done
rm -rf output-jeffrey-block-study
