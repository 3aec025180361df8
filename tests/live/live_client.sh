#!/usr/bin/env bash
# A scripted live client for tissuefem's 'Tool/Live port' (tests/live):
#   live_client.sh TISSUEFEM EXPECTED_OUTPUT WORKDIR MODE
# starts tissuefem on live_pull_bar.prm in WORKDIR, reads the port it
# listens on from results/live_port, connects over 127.0.0.1 (bash's
# /dev/tcp) and, by MODE:
#   full    sends the positions 0.1 t at 500 Hz for t in [0, 1], reading the
#           force answered to each, then 'bye'; tissuefem must exit 0 and its
#           summary file equal EXPECTED_OUTPUT (the closed form of
#           prm/tool_pull_bar_1d), and every answer must be a line of
#           finite numbers;
#   silent  sends positions up to t = 0.3 and then nothing: tissuefem must
#           end the run after its 'Live timeout' (1 s) with exit status 0,
#           say why, and leave complete outputs up to t = 0.25.
set -u
exe=$1 expected=$2 work=$3 mode=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "live test ($mode): $*"; kill "$pid" 2>/dev/null; exit 1; }
"$exe" "$here/live_pull_bar.prm" > run.log 2>&1 &
pid=$!
for _ in $(seq 100); do [ -s results/live_port ] && break; sleep 0.1; done
[ -s results/live_port ] || fail "no results/live_port after 10 s"
port=$(cat results/live_port)
exec 3<>"/dev/tcp/127.0.0.1/$port" || fail "cannot connect to port $port"
last=500
[ "$mode" = silent ] && last=150
for k in $(seq 0 $last); do
  line=$(awk -v k="$k" 'BEGIN { printf "%.6g %.6g", k * 0.002, 0.1 * k * 0.002 }')
  echo "$line" >&3
  read -r -t 10 answer <&3 || fail "no answer to '$line'"
  set -- $answer
  [ $# -eq 2 ] || fail "answer '$answer' to '$line' is not 't f'"
  awk -v a="$1" -v b="$2" 'BEGIN { exit !(a == a + 0 && b == b + 0) }' ||
    fail "answer '$answer' is not numeric"
done
if [ "$mode" = full ]; then
  echo bye >&3
fi
wait "$pid"
status=$?
exec 3>&-
[ "$status" -eq 0 ] || { cat run.log; fail "tissuefem exited with status $status"; }
if [ "$mode" = full ]; then
  numdiff -q -a 1e-8 -r 1e-6 output "$expected" > /dev/null ||
    { diff output "$expected"; fail "results differ from the closed form"; }
else
  grep -q "live session ended at t = 0.25: the client sent nothing" run.log ||
    { cat run.log; fail "the run did not end at t = 0.25 naming the silent client"; }
  tail -c 1 results/tool_force.csv | od -c | grep -q '\\n' || fail "tool_force.csv is cut off"
  grep -q '^0.25,' results/tool_force.csv || fail "tool_force.csv lacks t = 0.25"
fi
echo "live test ($mode): ok"
