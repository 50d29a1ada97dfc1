#!/usr/bin/env bash
# moraine: one SIGINT stops Lua code too (a count hook, src/lua/lua_interrupt.c),
# with the checkpoint of the simulation and exit status 130:
#  - loop:   an endless Lua loop after a run: the deck line, the state at
#            step 3 in loop_interrupted.h5, which mpm.load continues from;
#  - hook:   a hook looping for ever inside a run: the run's own message and
#            checkpoint, after step 10;
#  - c_hook: a hook inside a slow C function: the signal waits for the C
#            function to return, then stops the run as above;
#  - seed:   a seeding of 6.4e7 points stops between rows of cells, adding no
#            particle, and the deck's other simulation is saved.
# Each deck must end within 10 s of the signal (it never ends by itself).
# case: signals | SIGINT while a deck runs an endless Lua loop: stopped at its line, checkpoint, exit 130
# expect: sigint_lua\.lua:[0-9]+: interrupted by signal 2; the state at step 3 is in .*/loop_interrupted\.h5$
# usage: sigint_lua.sh MORAINE OUTDIR
set -u
moraine=$1 out=$2 here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
fail=0

# interrupt MODE: runs the deck in MODE, sends one SIGINT once it has started,
# and checks the exit status and the last line of stderr against REGEX
interrupt() {
  local mode=$1 regex=$2 dir="$out/$1"
  mkdir -p "$dir"
  "$moraine" "$here/sigint_lua.lua" -q -o "$dir" --set mode="$mode" 2>"$dir/stderr.txt" &
  local pid=$!
  for _ in $(seq 1 600); do [ -e "$dir/started" ] && break; sleep 0.05; done
  [ -e "$dir/started" ] || { echo "FAIL: $mode: the deck did not start"; fail=1; }
  kill -INT $pid
  for _ in $(seq 1 100); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done
  if kill -0 $pid 2>/dev/null; then
    echo "FAIL: $mode: still running 10 s after one SIGINT"
    kill -KILL $pid
    fail=1
  fi
  wait $pid
  local status=$?
  [ $status -eq 130 ] || { echo "FAIL: $mode: exit status $status, expected 130"; fail=1; }
  local said
  said=$(tail -n 1 "$dir/stderr.txt")
  grep -Eq -- "$regex" <<<"$said" || { echo "FAIL: $mode: message does not match /$regex/: $said"; fail=1; }
  [ -z "$(find "$dir" -name '.*.tmp.*')" ] || { echo "FAIL: $mode: temporary files left"; fail=1; }
}

expect=$(sed -n 's/^# expect: //p' "$0")
interrupt loop "$expect"
interrupt hook "run\{\}: interrupted by signal 2 after step 10 \(t = [0-9.e-]+ s\); the state at step 10 is in .*/hook_interrupted\.h5"
interrupt seed "add_particles\(\): interrupted by signal 2 while seeding; the state at step 0 is in .*/seed_interrupted\.h5"
interrupt c_hook "run\{\}: interrupted by signal 2 after step 10 \(t = [0-9.e-]+ s\); the state at step 10 is in .*/c_hook_interrupted\.h5"

# the checkpoints hold the states named, and a run goes on from the first
cat >"$out/check.lua" <<'LUA'
for mode, step in pairs{ loop = 3, hook = 10, c_hook = 10 } do
  local sim = mpm.load(mpm.outdir .. "/" .. mode .. "/" .. mode .. "_interrupted.h5", { diagnostics = false })
  assert(sim:step() == step, mode .. ": checkpoint at step " .. sim:step() .. ", expected " .. step)
end
local sim = mpm.load(mpm.outdir .. "/loop/loop_interrupted.h5", { diagnostics = false })
sim:run{ steps = 2 }
assert(sim:step() == 5)
LUA
"$moraine" "$out/check.lua" -q -o "$out" || { echo "FAIL: the checkpoints do not load as expected"; fail=1; }

echo "message: $(tail -n 1 "$out/loop/stderr.txt" | sed 's/^moraine: //')"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
