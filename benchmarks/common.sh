# The start every benchmark script shares (sourced, bash): strict mode; exe,
# the tissuefem executable (the script's first argument, build/tissuefem by
# default); top, the repository; a scratch directory, entered and removed at
# exit; value, to read a run's summary.
set -euo pipefail
exe=$(realpath "${1:-build/tissuefem}")
top=$(realpath "$(dirname "${BASH_SOURCE[0]}")/..")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# The value of key $2 in output directory $1's run.txt (the number before
# the comment giving its units).
value() {
  sed -n "s/^$2 = \([^ ]*\).*/\1/p" "$1/run.txt"
}
