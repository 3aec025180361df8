#!/usr/bin/env bash
# A scripted live client for tissuefem's 'Tool/Live port' and 'Contact
# tool/Live port' (tests/live):
#   live_client.sh TISSUEFEM EXPECTED_OUTPUT WORKDIR MODE [SCENE POSITION]
# starts tissuefem on SCENE (default live_pull_bar.prm) in WORKDIR, reads
# the port it
# listens on from results/live_port, connects over 127.0.0.1 (bash's
# /dev/tcp) and, by MODE:
#   full    sends the positions POSITION (awk expressions of t separated by
#           spaces; default the bar's 0.1*t) at 500 Hz for t in [0, 1], reading the
#           force answered to each, then 'bye'; tissuefem must exit 0 and its
#           summary file equal EXPECTED_OUTPUT (the closed form of
#           prm/tool_pull_bar_1d), and every answer must be a line of
#           finite numbers, one per coordinate and the time;
#   glitch  as full, with two bad positions sent among the good ones at
#           t = 0.4: one far outside the scene (1e308) and one jumping 0.16
#           from the last (more than a tenth of the bar): each must be
#           answered with a line starting 'refused', the run must go on
#           with the last good target, report 2 refused positions, and
#           give the same closed form;
#   silent  sends positions up to t = 0.3 and then nothing: tissuefem must
#           end the run after its 'Live timeout' (1 s) with exit status 0,
#           say why, and leave complete outputs up to t = 0.25.
set -u -f
exe=$1 expected=$2 work=$3 mode=$4
here=$(cd "$(dirname "$0")" && pwd)
scene=${5:-$here/live_pull_bar.prm}
position=${6:-0.1*t}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "live test ($mode): $*"; kill "$pid" 2>/dev/null; exit 1; }
"$exe" "$scene" > run.log 2>&1 &
pid=$!
for _ in $(seq 100); do [ -s results/live_port ] && break; sleep 0.1; done
[ -s results/live_port ] || fail "no results/live_port after 10 s"
port=$(cat results/live_port)
exec 3<>"/dev/tcp/127.0.0.1/$port" || fail "cannot connect to port $port"
last=500
[ "$mode" = silent ] && last=150
# Every line 't x [y [z]]' at t = 0.002 k, k = 0..last, from one awk run
# (a process per line and per answer's value made the test 40 s of forks).
program='BEGIN { for (k = 0; k <= last; ++k) { t = k * 0.002; printf "%.6g", t'
for c in $position; do program+="; printf \" %.6g\", $c"; done
program+='; printf "\n" } }'
mapfile -t lines < <(awk -v last="$last" "$program")
[ ${#lines[@]} -eq $((last + 1)) ] || fail "cannot compute the positions"
# A finite number (no inf, no nan).
number='^[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?$'
for k in $(seq 0 $last); do
  line=${lines[$k]}
  echo "$line" >&3
  read -r -t 10 answer <&3 || fail "no answer to '$line'"
  set -- $answer
  words=($line)
  [ $# -eq ${#words[@]} ] ||
    fail "answer '$answer' to '$line' is not 't f...' (one per coordinate)"
  for value in "$@"; do
    [[ $value =~ $number ]] || fail "answer '$answer' is not numeric"
  done
  if [ "$mode" = glitch ] && [ "$k" -eq 200 ]; then
    for bad in "0.4001 1e308" "0.4002 0.2"; do
      echo "$bad" >&3
      read -r -t 10 answer <&3 || fail "no answer to the bad position '$bad'"
      case "$answer" in
        refused*) ;;
        *) fail "the bad position '$bad' was answered '$answer', not refused" ;;
      esac
    done
  fi
done
if [ "$mode" != silent ]; then
  echo bye >&3
fi
wait "$pid"
status=$?
exec 3>&-
[ "$status" -eq 0 ] || { cat run.log; fail "tissuefem exited with status $status"; }
if [ "$mode" != silent ]; then
  numdiff -q -a 1e-8 -r 1e-6 output "$expected" > /dev/null ||
    { diff output "$expected"; fail "results differ from the closed form"; }
  if [ "$mode" = glitch ]; then
    grep -q "refused 2 positions" run.log ||
      { cat run.log; fail "the run does not report the 2 refused positions"; }
  fi
else
  grep -q "live session ended at t = 0.25: the client sent nothing" run.log ||
    { cat run.log; fail "the run did not end at t = 0.25 naming the silent client"; }
  tail -c 1 results/tool_force.csv | od -c | grep -q '\\n' || fail "tool_force.csv is cut off"
  grep -q '^0.25,' results/tool_force.csv || fail "tool_force.csv lacks t = 0.25"
fi
echo "live test ($mode): ok"
