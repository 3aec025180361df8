#!/bin/sh
# Reproduces Jeffrey's table E.1: runs parameters/jeffrey_table_e1.prm with
# each Jacobian kind and prints the per-interval means beside the report's.
# Usage (from the repository top, after building): 
#   sh parameters/studies/jeffrey_table_e1.sh [path/to/tissuefem]
set -e
exe=${1:-build/tissuefem}
prm=$(dirname "$0")/../jeffrey_table_e1.prm
printf '%-12s | %-31s | %-31s\n' "" "this run (per 0.05 s interval)" "Jeffrey's table E.1"
printf '%-12s | %7s %7s %7s %7s | %7s %7s %7s %7s\n' Jacobian "h (s)" "RK" "J" "Newton" "h (s)" "RK" "J" "Newton"
for kind in numerical analytical simplified; do
  case $kind in
    numerical) report="0.0200     2.5     2.4     7.7";;
    analytical) report="0.0336     1.5     1.5     4.0";;
    simplified) report="0.0052     9.5     Nil    49.6";;
  esac
  line=$("$exe" "$prm" --set "Time integration/Radau IIA/Jacobian=$kind" \
           --set "Output/Directory=output-jeffrey-table-e1-$kind" | grep '^Radau IIA')
  echo "$line" | sed -e 's/.*mean Runge-Kutta step \([^ ]*\).*Runge-Kutta steps \([^,]*\),.*Jacobian evaluations \([^,]*\), Newton iterations \(.*\)/\1 \2 \3 \4/' |
    awk -v k=$kind -v r="$report" '{ printf "%-12s | %7.4f %7.1f %7.1f %7.1f |  %s\n", k, $1, $2, $3, $4, r }'
done
