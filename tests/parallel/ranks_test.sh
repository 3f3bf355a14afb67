#!/usr/bin/env bash
# Distributed runs under mpirun (docs/parallel.md), against the one-rank run of the same input.
# Usage: ranks_test.sh MODE SUS ARGS...
#   agree INPUT STEPS            1, 2, 3 and 4 ranks agree after STEPS steps (compare_runs.py:
#                                1e-9 of each array's scale, totals to 1e-12); 2 ranks twice
#                                write the same bytes
#   restart INPUT STEPS FROM TO  FROM ranks stop at 3/5 of STEPS, TO ranks continue from the
#                                checkpoint to STEPS; agrees with one rank
#   resume INPUT STEPS STOP      2 ranks stopped at STOP (--max-timesteps) and restarted on 2
#                                write the uninterrupted 2-rank run's files byte for byte
#   decompose INPUT RANKS        sus --decompose RANKS prints the boxes and imbalance a RANKS-rank
#                                run draws at setup
#   setup INPUT                  4 ranks each set up only their box: the largest rank's memory
#                                after setup at most 0.75 of one rank's, the particles the same
#                                as one rank's at step 0
#   chain INPUT STEPS R1 R2 R3   R1 ranks, restarted on R2 then R3: each restart's rank that read
#                                most read at most 0.6 of the checkpoint; agrees with one rank
#   kill INPUT STEPS             a rank of 3 is killed (SIGKILL) at a random moment: the job ends
#                                within 60 s, every output file is complete, a 2-rank restart agrees
#   badinput INPUT               3 ranks: exit code 2, the file:line message once, within 30 s
#   badrank GOOD BAD             3 ranks, one (then two) of them given BAD: the same, every rank
#   stop INPUT [RANKS]           RANKS ranks (3 unless given) stop on a diagnostic one of them
#                                finds: exit code 3 in the step of one rank, its message once,
#                                the last good state of one rank written
#   paraview INPUT STEPS         VTK's own reader opens the .pvd of a 3-rank run: every time, all
#                                particles, every array; its pictures are the 1-rank ones (the
#                                same bytes at t = 0, at most 0.1% of the pixels differ later)
#   rebalance INPUT STEPS        2 ranks draw their boxes anew as the particles drift, and agree
#                                with one rank
#   signal INPUT STEPS           SIGUSR1 to mpirun (2 ranks), then SIGTERM to the rank processes
#                                themselves: exit code 4 from mpirun, the message once, a
#                                checkpoint and the last output at the last step; the first stop's
#                                2-rank restart agrees with one rank after STEPS more steps
# TOLERANCE (environment) replaces compare_runs.py's 1e-9 of each array's scale.
set -uo pipefail
mode=$1
sus=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
compare="/usr/bin/python3 $here/compare_runs.py --tolerance ${TOLERANCE:-1e-9}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_WAIT_POLICY=passive
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*"
  exit 1
}
# launch N LOG ARGS...: sus ARGS on N ranks of one thread (N = 1: no mpirun), its output in LOG.
launch() {
  local n=$1 log=$2
  shift 2
  if [ "$n" = 1 ]; then
    "$sus" --threads 1 "$@" > "$log" 2>&1
  else
    timeout 300 mpirun -np "$n" "$sus" --threads 1 "$@" > "$log" 2>&1
  fi
}
run() {  # N DIR ARGS...: a run with output in DIR, its log in DIR.log
  local n=$1 dir=$2
  shift 2
  launch "$n" "$dir.log" -o "$dir" "$@"
}
restartRun() {  # N DIR ARGS...: the run in DIR continued, its log in DIR.restart.log
  local n=$1 dir=$2
  shift 2
  launch "$n" "$dir.restart.log" -restart "$dir" "$@"
}
# The particle file of step S in DIR (.vtu of one rank, .pvtu of several).
stepFile() {
  local f
  f=$(ls "$1"/particles/step_$(printf %06d "$2").vtu "$1"/particles/step_$(printf %06d "$2").pvtu 2>/dev/null | head -1)
  [ -n "$f" ] || fail "$1 has no output of step $2"
  echo "$f"
}

case $mode in
  agree)
    input=$1 steps=$2
    run 1 "$work/r1" --max-timesteps "$steps" "$input" || fail "1 rank: exit $? ($(tail -3 "$work/r1.log"))"
    for n in 2 3 4; do
      run $n "$work/r$n" --max-timesteps "$steps" "$input" || fail "$n ranks: exit $? ($(tail -3 "$work/r$n.log"))"
      grep "ranks:" "$work/r$n.log" | head -1
      $compare "$(stepFile "$work/r1" "$steps")" "$(stepFile "$work/r$n" "$steps")" | tail -3 ||
        fail "$n ranks differ from 1"
    done
    run 2 "$work/again" --max-timesteps "$steps" "$input" || fail "2 ranks again: exit $?"
    for f in "$work"/r2/particles/*.vtu; do
      cmp -s "$f" "$work/again/particles/$(basename "$f")" || fail "2 ranks twice: $(basename "$f") differs"
    done
    echo "2 ranks twice: the same bytes"
    ;;
  restart)
    input=$1 steps=$2 from=$3 to=$4
    run 1 "$work/reference" --max-timesteps "$steps" "$input" || fail "reference: exit $?"
    run "$from" "$work/r" --max-timesteps $((steps * 3 / 5)) "$input" || fail "$from ranks: exit $?"
    restartRun "$to" "$work/r" --max-timesteps "$steps" || fail "restart on $to ranks: exit $? ($(tail -3 "$work/r.restart.log"))"
    grep "restarting\|shared out" "$work/r.restart.log"
    $compare "$(stepFile "$work/reference" "$steps")" "$(stepFile "$work/r" "$steps")" | tail -3 ||
      fail "$from -> $to ranks differs from 1 rank"
    # The summary's bytes per step are of the steps this process ran, after the restart.
    [ "$to" -eq 1 ] || /usr/bin/python3 - "$work/r.restart.log" <<'EOF' || fail "bytes per step not over the steps after the restart"
import re, sys
log = open(sys.argv[1]).read()
steps = int(re.search(r"after the restart: (\d+) steps", log).group(1))
total, per = map(float, re.search(r"sent (\S+) bytes in all, (\S+) per step", log).groups())
print("sent %.4g bytes in the %d steps after the restart: %.4g per step; the summary: %.4g" % (total, steps, total / steps, per))
sys.exit(abs(per - total / steps) > 1e-2 * total / steps)  # both printed to 4 digits
EOF
    ;;
  resume)
    input=$1 steps=$2 stop=$3
    run 2 "$work/whole" --max-timesteps "$steps" "$input" || fail "uninterrupted: exit $?"
    run 2 "$work/r" --max-timesteps "$stop" "$input" || fail "stopped: exit $?"
    grep "boxes drawn anew" "$work/whole.log" "$work/r.log"
    restartRun 2 "$work/r" --max-timesteps "$steps" || fail "restart: exit $? ($(tail -3 "$work/r.restart.log"))"
    for f in "$work"/whole/particles/*.vtu; do
      cmp -s "$f" "$work/r/particles/$(basename "$f")" || fail "$(basename "$f") differs after the restart"
    done
    for run in whole r; do  # history.csv without its wall time
      awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "wall_seconds") w = i }
                        { if (w) $w = ""; print }' "$work/$run/history.csv" > "$work/$run.csv"
    done
    cmp -s "$work/whole.csv" "$work/r.csv" || fail "history.csv differs after the restart"
    echo "stopped at step $stop, restarted: the uninterrupted run's files"
    ;;
  decompose)
    # sus --decompose N (one process) draws the boxes an N-rank run draws at setup, with the same
    # imbalance; under mpirun it is an error.
    input=$1 ranks=$2
    "$sus" --decompose "$ranks" "$input" > "$work/dry.txt" 2>&1 || fail "--decompose: exit $?"
    cat "$work/dry.txt"
    launch "$ranks" "$work/run.log" -o "$work/r" --max-timesteps 1 "$input" || fail "$ranks ranks: exit $?"
    boxes=$(sed -n "s/^sus --decompose $ranks: //p" "$work/dry.txt")
    grep -qF "sus: $ranks ranks: $boxes," "$work/run.log" ||
      fail "the run drew other boxes: $(grep "ranks:" "$work/run.log")"
    dry=$(sed -n 's/^  recursive bisection.*imbalance (most \/ mean) \([0-9.]*\).*/\1/p' "$work/dry.txt")
    run=$(sed -n 's/.*particles per rank max\/mean \([0-9.]*\)$/\1/p' "$work/run.log" | head -1)
    /usr/bin/python3 -c "import sys; sys.exit(abs($dry - $run) > 1e-3)" ||
      fail "imbalance $dry dry, $run in the run"
    echo "imbalance $dry, as the run's $run"
    timeout 30 mpirun -np 2 "$sus" --decompose 2 "$input" > "$work/mpi.txt" 2>&1
    [ $? = 2 ] || fail "--decompose under mpirun: not exit 2"
    ;;
  setup)
    input=$1
    run 1 "$work/r1" --max-timesteps 1 "$input" || fail "1 rank: exit $?"
    run 4 "$work/r4" --max-timesteps 1 "$input" || fail "4 ranks: exit $?"
    /usr/bin/python3 - "$work/r1.log" "$work/r4.log" <<'EOF' || fail "4 ranks' setup memory not at most 0.75 of one rank's"
import re, sys
one = float(re.search(r"sus: setup .*peak memory ([0-9.]+) MB", open(sys.argv[1]).read()).group(1))
four = float(re.search(r"sus: setup .*peak memory ([0-9.]+) MB on the largest", open(sys.argv[2]).read()).group(1))
print(f"setup peak memory: 1 rank {one} MB, the largest of 4 ranks {four} MB ({four / one:.2f})")
sys.exit(0 if four <= 0.75 * one else 1)
EOF
    $compare "$(stepFile "$work/r1" 0)" "$(stepFile "$work/r4" 0)" | tail -3 || fail "4 ranks' setup differs from 1"
    ;;
  chain)
    # A distributed run restarted on two other rank counts in turn: each restart's rank that read
    # most read at most 0.6 of the checkpoint (its share of the parts, not all of them), and the
    # end agrees with one rank.
    input=$1 steps=$2
    shift 2
    run 1 "$work/reference" --max-timesteps "$steps" "$input" || fail "reference: exit $?"
    n=$#
    k=1
    run "$1" "$work/r" --max-timesteps $((steps / n)) "$input" || fail "$1 ranks: exit $?"
    from=$1
    shift
    for to in "$@"; do
      k=$((k + 1))
      restartRun "$to" "$work/r" --max-timesteps $((steps * k / n)) ||
        fail "$from -> $to ranks: exit $? ($(tail -3 "$work/r.restart.log"))"
      line=$(grep "read most" "$work/r.restart.log") || fail "$from -> $to: no bytes-read line"
      echo "$from -> $to ranks: $line"
      fraction=$(echo "$line" | sed 's/.*(\([0-9.]*\))$/\1/')
      /usr/bin/python3 -c "import sys; sys.exit(float('$fraction') > 0.6)" ||
        fail "$from -> $to ranks: a rank read $fraction of the checkpoint"
      from=$to
    done
    $compare "$(stepFile "$work/reference" "$steps")" "$(stepFile "$work/r" "$steps")" | tail -3 ||
      fail "the chain of restarts differs from 1 rank"
    ;;
  kill)
    input=$1 steps=$2
    run 1 "$work/reference" --max-timesteps "$steps" "$input" || fail "reference: exit $?"
    timeout 300 mpirun -np 3 "$sus" --threads 1 -o "$work/r" --max-timesteps "$steps" "$input" > "$work/r.log" 2>&1 &
    job=$!
    # A moment within the run: after its first output, within the time a one-rank run took.
    for _ in $(seq 300); do [ -e "$work/r/particles.pvd" ] && break; sleep 0.1; done
    sleep "$(/usr/bin/python3 -c "import random; print(round(random.uniform(0, 0.8) * $(grep -o 'wall [0-9.]*' "$work/reference.log" | cut -d' ' -f2), 2))")"
    victim=$(pgrep -f -- "^$sus .*-o $work/r " | shuf -n 1)
    if [ -n "$victim" ]; then
      kill -9 "$victim" && echo "killed rank process $victim (SIGKILL)"
    else
      echo "the run ended before the kill"
    fi
    for _ in $(seq 60); do kill -0 $job 2>/dev/null || break; sleep 1; done
    kill -0 $job 2>/dev/null && fail "the job still runs 60 s after a rank was killed"
    wait $job
    echo "the job ended (exit $?)"
    # Every file under its final name is complete: each output the .pvd lists opens.
    if [ -e "$work/r/particles.pvd" ]; then
      /usr/bin/python3 "$here/read_series.py" "$work/r/particles.pvd" --any || fail "incomplete output after the kill"
    else
      echo "killed before the first output"
    fi
    if ls "$work"/r/checkpoints/*.ckpt > /dev/null 2>&1; then
      restartRun 2 "$work/r" --max-timesteps "$steps" || fail "restart after the kill: exit $?"
      $compare "$(stepFile "$work/reference" "$steps")" "$(stepFile "$work/r" "$steps")" | tail -1 ||
        fail "the restart after the kill differs from 1 rank"
    else
      echo "killed before the first checkpoint"
    fi
    ;;
  signal)
    input=$1 steps=$2
    # stopRun SIGNAL DIR: a 2-rank run stopped by SIGNAL ("mpirun": SIGUSR1 to mpirun, "ranks":
    # SIGTERM to its rank processes) a second into its steps; prints the step it stopped after.
    stopRun() {
      mpirun -np 2 "$sus" --threads 1 -o "$2" "$input" > "$2.log" 2>&1 &
      local job=$!
      for _ in $(seq 300); do ls "$2"/checkpoints/*.ckpt > /dev/null 2>&1 && break; sleep 0.1; done
      sleep 1
      if [ "$1" = mpirun ]; then kill -USR1 $job; else pkill -TERM -P $job; fi
      wait $job
      local code=$?
      [ $code = 4 ] || fail "$1: exit code $code, not 4 ($(tail -3 "$2.log"))"
      [ "$(grep -c "stopped on request" "$2.log")" = 1 ] || fail "$1: the stop reported $(grep -c "stopped on request" "$2.log") times"
      local last
      last=$(tail -1 "$2/history.csv" | cut -d, -f1)
      ls "$2"/checkpoints/*step_$(printf %06d "$last").ckpt > /dev/null 2>&1 ||
        fail "$1: no checkpoint at the last step $last ($(ls "$2"/checkpoints))"
      grep -q "step_$(printf %06d "$last").pvtu" "$2/particles.pvd" || fail "$1: no output of the last step $last"
      echo "$last"
    }
    stopped=$(stopRun mpirun "$work/r") || fail "$stopped"
    echo "SIGUSR1 to mpirun: every rank stopped after step $stopped, exit 4"
    again=$(stopRun ranks "$work/t") || fail "$again"
    echo "SIGTERM to the ranks: stopped after step $again, exit 4"
    end=$((stopped + steps))
    run 1 "$work/reference" --max-timesteps "$end" "$input" || fail "reference: exit $?"
    restartRun 2 "$work/r" --max-timesteps "$end" || fail "restart: exit $?"
    grep -q "restarting from .*step_$(printf %06d "$stopped").ckpt" "$work/r.restart.log" ||
      fail "the restart did not start at step $stopped: $(grep restarting "$work/r.restart.log")"
    [ -e "$work/r/particles/step_$(printf %06d "$stopped").pvtu" ] && ! /usr/bin/python3 -c "import sys; sys.exit(0 if 'step_$(printf %06d "$stopped").pvtu' in open('$work/r/particles.pvd').read() else 1)" &&
      fail "the stop's output is left out of the series but not removed"
    $compare "$(stepFile "$work/reference" "$end")" "$(stepFile "$work/r" "$end")" | tail -1 ||
      fail "the restart after the stop differs from 1 rank"
    ;;
  badinput)
    input=$1
    start=$(date +%s)
    timeout 30 mpirun -np 3 "$sus" --threads 1 -o "$work/r" "$input" > "$work/r.log" 2>&1
    code=$?
    [ $code = 124 ] && fail "no end within 30 s"
    [ $code = 2 ] || fail "exit code $code, not 2"
    count=$(grep -c "$(basename "$input"):[0-9]*:" "$work/r.log")
    [ "$count" = 1 ] || fail "the message appears $count times: $(cat "$work/r.log")"
    [ -e "$work/r" ] && fail "output written for a bad input"
    grep "$(basename "$input"):" "$work/r.log"
    echo "exit 2 after $(($(date +%s) - start)) s"
    ;;
  badrank)
    # One rank's input differs from the others' (an input path not shared between nodes): the
    # bad one on rank 2 of 3, then on ranks 0 and 1 (MPMD launches). Every rank ends within 30 s
    # with exit 2, the bad rank's message printed once, no output written.
    good=$1 bad=$2
    for layout in "2 $good 1 $bad" "2 $bad 1 $good"; do
      set -- $layout
      rm -rf "$work/r"
      timeout 30 mpirun -np "$1" "$sus" --threads 1 -o "$work/r" "$2" : \
        -np "$3" "$sus" --threads 1 -o "$work/r" "$4" > "$work/r.log" 2>&1
      code=$?
      [ $code = 124 ] && fail "$layout: no end within 30 s ($(tail -3 "$work/r.log"))"
      [ $code = 2 ] || fail "$layout: exit code $code, not 2 ($(tail -3 "$work/r.log"))"
      count=$(grep -c "$(basename "$bad"):[0-9]*:" "$work/r.log")
      [ "$count" = 1 ] || fail "$layout: the message appears $count times: $(cat "$work/r.log")"
      [ -e "$work/r" ] && fail "$layout: output written for a bad input"
      grep "$(basename "$bad"):" "$work/r.log"
    done
    ;;
  stop)
    input=$1 ranks=${2:-3}
    run 1 "$work/r1" "$input"
    [ $? = 3 ] || fail "1 rank: exit code not 3"
    run "$ranks" "$work/rn" "$input"
    code=$?
    [ $code = 3 ] || fail "$ranks ranks: exit code $code, not 3 ($(tail -5 "$work/rn.log"))"
    count=$(grep -c "simulation stopped" "$work/rn.log")
    [ "$count" = 1 ] || fail "the diagnostic appears $count times"
    grep "simulation stopped" "$work/r1.log" | sed 's/^/1 rank:  /'
    grep "simulation stopped" "$work/rn.log" | sed "s/^/$ranks ranks: /"
    # An implicit stop ends with Newton's ratios, and names the particle's place, which differ
    # with the rank count's preconditioner in their digits: the messages are compared without them.
    stopLine() { grep "simulation stopped" "$1" | sed "s/ Newton's ratios .*//; s/ at \[[^]]*\]//"; }
    [ "$(stopLine "$work/r1.log")" = "$(stopLine "$work/rn.log")" ] ||
      fail "$ranks ranks stop elsewhere than 1 rank"
    last1=$(grep -o 'file="[^"]*"' "$work/r1/particles.pvd" | tail -1 | sed 's/.*step_\([0-9]*\).*/\1/')
    lastN=$(grep -o 'file="[^"]*"' "$work/rn/particles.pvd" | tail -1 | sed 's/.*step_\([0-9]*\).*/\1/')
    [ "$last1" = "$lastN" ] || fail "last good state: step $lastN on $ranks ranks, $last1 on 1"
    $compare "$(stepFile "$work/r1" $((10#$last1)))" "$(stepFile "$work/rn" $((10#$lastN)))" | tail -1 ||
      fail "the last good states differ"
    ;;
  paraview)
    input=$1 steps=$2
    run 1 "$work/r1" --max-timesteps "$steps" "$input" || fail "1 rank: exit $?"
    run 3 "$work/r3" --max-timesteps "$steps" "$input" || fail "3 ranks: exit $?"
    /usr/bin/python3 "$here/read_series.py" "$work/r3/particles.pvd" --like "$work/r1/particles.pvd" ||
      fail "the 3-rank series does not read as the 1-rank one"
    /usr/bin/python3 "$here/compare_pictures.py" "$work/r1/images" "$work/r3/images" ||
      fail "the 3-rank pictures differ from the 1-rank ones in more than 0.1% of their pixels"
    # At t = 0 the particles are the same to the bit: the composited picture is the same file.
    for f in "$work"/r1/images/*_0.png; do
      cmp -s "$f" "$work/r3/images/$(basename "$f")" || fail "$(basename "$f") of 3 ranks is not 1 rank's"
      echo "$(basename "$f"): 3 ranks the same bytes as 1"
    done
    ;;
  rebalance)
    input=$1 steps=$2
    run 1 "$work/r1" --max-timesteps "$steps" "$input" || fail "1 rank: exit $?"
    run 2 "$work/r2" --max-timesteps "$steps" "$input" || fail "2 ranks: exit $?"
    grep "boxes drawn anew" "$work/r2.log" || fail "no rebalance"
    $compare "$(stepFile "$work/r1" "$steps")" "$(stepFile "$work/r2" "$steps")" | tail -1 ||
      fail "2 ranks with rebalancing differ from 1 rank"
    ;;
  *)
    fail "unknown mode $mode"
    ;;
esac
echo PASS
