#!/usr/bin/env bash
# moraine: the command line (doc/lua-api.md, "Command line").
# case: warnings | a --set NAME that no mpm.param call of the deck reads
# expect: warning \[unused_set\]: --set tiem=0\.2 \(did you mean 'time'\?\), --set zz=1: never read by mpm\.param, so they changed nothing
#
#  - GNU long options: --output=DIR, --output DIR, -o DIR and an
#    abbreviation (--out DIR) put the outputs in DIR; a long option without
#    a value and an ambiguous abbreviation are command-line errors (status 2);
#  - "-" reads the deck from standard input: it runs, its errors name
#    "stdin:LINE", its provenance copy is the text it read;
#  - a --set the deck never reads with mpm.param is warned about once, at
#    the end, with the nearest name it reads; --ignore-warning unused_set
#    silences it; a deck that reads every --set gets no warning.
# usage: cli.sh MORAINE OUTDIR
set -u
moraine=$1 out=$2
rm -rf "$out"; mkdir -p "$out"
expect=$(sed -n 's/^# expect: //p' "$0")
fail=0
deck=$out/deck.lua
cat > "$deck" <<'LUA'
local time = mpm.param("time", 0.1)
local mu = mpm.param("mu", 0.3)
io.open(mpm.outdir .. "/ran.txt", "w"):write(string.format("%g %g\n", time, mu)):close()
LUA
for way in "--output=$out/a" "--output $out/b" "-o $out/c" "--out $out/d" "-o$out/e"; do
  dir=${way##*[ =]}; dir=${dir#-o}
  # shellcheck disable=SC2086 # the option and its value are words
  "$moraine" "$deck" -q $way --set time=0.5 2>/dev/null && [ "$(cat "$dir/ran.txt" 2>/dev/null)" = "0.5 0.3" ] ||
    { echo "FAIL: '$way' did not put the outputs in $dir"; fail=1; }
done
for bad in "--output" "--qu=1" "--s=1"; do
  "$moraine" "$deck" "$bad" 2>/dev/null
  [ $? -eq 2 ] || { echo "FAIL: '$bad' is not a command-line error"; fail=1; }
done

# the deck on standard input
printf 'local n = mpm.param("n", 1)\nprint("from stdin", mpm.deck, n)\n' > "$out/stdin.lua"
said=$("$moraine" - -q -o "$out/stdin" --set n=3 < "$out/stdin.lua") && [ "$said" = "$(printf 'from stdin\t-\t3.0')" ] ||
  { echo "FAIL: a deck on stdin said '$said'"; fail=1; }
cmp -s "$out/stdin.lua" "$out/stdin/provenance/deck.lua" || { echo "FAIL: the provenance copy of stdin differs"; fail=1; }
err=$(printf 'local a = 1\nerror("on line two")\n' | "$moraine" - -q -o "$out/stdin_err" 2>&1)
[ $? -eq 1 ] && grep -q "stdin:2: on line two" <<<"$err" || { echo "FAIL: an error on stdin said '$err'"; fail=1; }

# --set never read
err=$("$moraine" "$deck" -q -o "$out/unused" --set tiem=0.2 --set mu=0.1 --set zz=1 2>&1 >/dev/null) ||
  { echo "FAIL: the run with an unused --set failed: $err"; fail=1; }
grep -Eq -- "$expect" <<<"$err" || { echo "FAIL: message does not match /$expect/: $err"; fail=1; }
[ "$(grep -c unused_set <<<"$err")" -eq 1 ] || { echo "FAIL: the warning is not printed once: $err"; fail=1; }
err=$("$moraine" "$deck" -q -o "$out/unused" --set tiem=0.2 --ignore-warning unused_set 2>&1 >/dev/null)
[ -z "$err" ] || { echo "FAIL: --ignore-warning unused_set still printed: $err"; fail=1; }
err=$("$moraine" "$deck" -q -o "$out/unused" --set time=0.2 --set mu=1 2>&1 >/dev/null)
[ -z "$err" ] || { echo "FAIL: a deck reading every --set got: $err"; fail=1; }
echo "message: $(grep unused_set <<<"$("$moraine" "$deck" -q -o "$out/unused" --set tiem=0.2 --set zz=1 2>&1)" | sed 's/^moraine: //')"
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
