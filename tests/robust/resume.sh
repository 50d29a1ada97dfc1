#!/usr/bin/env bash
# moraine: a run stopped at a random step (seeded, printed) and continued
# with --restart into the same directory leaves the outputs of a straight
# run: SIGINT (from <name>_interrupted.h5), SIGKILL (from the newest
# periodic checkpoint), and SIGINT continued by a deck with mpm.resume. A second run into that directory is refused naming
# the files; --overwrite lets it; a run while another holds the directory
# is refused naming the process.
# case: files | a run interrupted and resumed with --restart equals a straight run
# expect: run\{\}: the output directory '.*' holds this simulation's outputs of another run: '.*block\.pvd', '.*block_000000\.vtp' \(and [0-9]+ more \.vtp\), '.*diagnostics\.csv', '.*diagnostics\.h5'
# usage: resume.sh MORAINE OUTDIR [PYTHON]; the seed is MORAINE_RESUME_SEED, else the clock's
set -u
moraine=$1 out=$2 here=$(cd "$(dirname "$0")" && pwd)
seed=${MORAINE_RESUME_SEED:-$(date +%s)}
check="${3:-/usr/bin/python3} $here/check_resume.py"
deck=$here/resume_run.lua
rm -rf "$out"; mkdir -p "$out"
# the deck's run is 500 steps (two run{} calls: 200, then to t = 0.05)
RANDOM=$seed
int_at=$((1 + RANDOM % 499)) kill_at=$((251 + RANDOM % 249)) resume_at=$((201 + RANDOM % 299))
echo "seed $seed: SIGINT at step $int_at, SIGKILL at step $kill_at, SIGINT at step $resume_at for mpm.resume" \
  "(MORAINE_RESUME_SEED=$seed to repeat)"
fail=0
ok() { echo "ok: $*"; }
bad() { echo "FAIL: $*"; fail=1; }

# run the deck into $1 until it reaches step $2, then send signal $3
stop_at() {
  local dir=$1 step=$2 sig=$3
  "$moraine" "$deck" -q -o "$dir" --set stop_at=$step 2>"$dir.stderr.txt" &
  local pid=$!
  for _ in $(seq 1 1200); do [ -e "$dir/at_stop" ] && break; sleep 0.05; done
  kill -$sig $pid
  wait $pid
}

"$moraine" "$deck" -q -o "$out/straight" || bad "the straight run failed"

mkdir -p "$out/int"
stop_at "$out/int" $int_at INT
status=$?
[ $status -eq 130 ] || bad "SIGINT: exit status $status, expected 130"
rm -f "$out/int/at_stop"
"$moraine" "$deck" -q -o "$out/int" --restart "$out/int/block_interrupted.h5" 2>"$out/int.restart.txt" ||
  { bad "the restart after SIGINT failed"; cat "$out/int.restart.txt"; }
$check "$out/straight" "$out/int" && ok "SIGINT at step $int_at, --restart: outputs equal the straight run's" ||
  bad "SIGINT at step $int_at: outputs differ"

mkdir -p "$out/kill"
stop_at "$out/kill" $kill_at KILL
newest=$(ls "$out/kill"/block_checkpoint_*.h5 | tail -n 1)
rm -f "$out/kill/at_stop"
"$moraine" "$deck" -q -o "$out/kill" --restart "$newest" 2>"$out/kill.restart.txt" ||
  { bad "the restart after SIGKILL failed"; cat "$out/kill.restart.txt"; }
grep -q "took over the lock file" "$out/kill.restart.txt" && ok "the stale lock of the killed run was taken over" ||
  bad "no warning about the stale lock"
$check "$out/straight" "$out/kill" && ok "SIGKILL at step $kill_at, --restart $(basename "$newest"): outputs equal" ||
  bad "SIGKILL at step $kill_at: outputs differ"

# a deck continuing the checkpoint with mpm.resume (one in the second run{})
mkdir -p "$out/deck"
stop_at "$out/deck" $resume_at INT
rm -f "$out/deck/at_stop"
"$moraine" "$here/resume_deck.lua" -q -o "$out/deck" 2>"$out/deck.resume.txt" ||
  { bad "mpm.resume failed"; cat "$out/deck.resume.txt"; }
$check "$out/straight" "$out/deck" && ok "SIGINT at step $resume_at, mpm.resume: outputs equal" ||
  bad "SIGINT at step $resume_at, mpm.resume: outputs differ"

# --restart with a deck that never runs the checkpoint's simulation
"$moraine" "$deck" -q -o "$out/other" --set name=other --restart "$out/int/block_interrupted.h5" 2>"$out/other.txt"
status=$?
[ $status -eq 1 ] && grep -q "the deck never reached run{} #[12] of a simulation named 'block'" "$out/other.txt" &&
  ok "a deck without the checkpoint's simulation: $(cat "$out/other.txt")" ||
  { bad "--restart with another deck: exit $status"; cat "$out/other.txt"; }

# a second run into a directory holding a run's outputs
before=$(cat "$out/straight"/diagnostics.csv | md5sum)
"$moraine" "$deck" -q -o "$out/straight" 2>"$out/again.txt"
status=$?
expect=$(sed -n 's/^# expect: //p' "$0")
[ $status -eq 1 ] && grep -Eq -- "$expect" "$out/again.txt" && ok "a second run is refused" ||
  { bad "a second run into the directory: exit $status, expected 1 and /$expect/"; cat "$out/again.txt"; }
[ "$before" = "$(md5sum < "$out/straight"/diagnostics.csv)" ] || bad "the refused run changed diagnostics.csv"
"$moraine" "$deck" -q -o "$out/straight" --overwrite && ok "--overwrite replaces them" || bad "--overwrite failed"

# two runs at once into one directory
mkdir -p "$out/busy"
"$moraine" "$deck" -q -o "$out/busy" --set stop_at=5 2>/dev/null &
first=$!
for _ in $(seq 1 1200); do [ -e "$out/busy/at_stop" ] && break; sleep 0.05; done
"$moraine" "$deck" -q -o "$out/busy" 2>"$out/busy.txt"
status=$?
kill -INT $first; wait $first
[ $status -eq 1 ] && grep -q "is in use by another moraine run (process $first," "$out/busy.txt" &&
  ok "a concurrent run is refused: $(cat "$out/busy.txt")" || { bad "concurrent run: exit $status"; cat "$out/busy.txt"; }
[ -e "$out/busy/.moraine.lock" ] && bad "the lock file stays after the run"

echo "message: $(cat "$out/again.txt")"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed (seed $seed)"; fi
exit $fail
