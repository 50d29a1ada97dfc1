#!/usr/bin/env bash
# moraine: show that the working tree computes bit for bit what an earlier
# revision computes. Builds REV (default: HEAD) in a temporary worktree and
# the working tree in build-bitwise/, then
#   - runs the bench's problems with both (each once, on 1 and 2
#     threads) and compares their particle-state hashes;
#   - runs the decks of this directory with both and compares every
#     checkpoint they write, object by object (compare.py).
# Used for changes of structure that must not change a result (a refactor of
# the kernels, a new layer): a change of physics is expected to differ.
#
#   scripts/bitwise/run.sh [REV]        exit status 0 when everything agrees
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
rev=${1:-HEAD}
py=$(command -v /usr/bin/python3 || command -v python3)
work=$(mktemp -d /tmp/moraine-bitwise-XXXXXX)
trap 'git -C "$root" worktree remove --force "$work/old-src" >/dev/null 2>&1 || true' EXIT

build() { # SRC BUILD_DIR
  # the same flags on both sides: whether -march=native is the default
  # depends on the revision, and it changes which sums are fused
  cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release -DMORAINE_TESTS=OFF -DMORAINE_NATIVE=ON >/dev/null
  cmake --build "$2" -j2 --target moraine bench >/dev/null
}
git -C "$root" worktree add --detach "$work/old-src" "$rev" >/dev/null 2>&1
echo "bitwise: building $rev and the working tree"
build "$work/old-src" "$work/old-build"
build "$root" "$root/build-bitwise"

status=0
echo "bitwise: bench problems"
for side in old new; do
  bin=$([ $side = old ] && echo "$work/old-build" || echo "$root/build-bitwise")/moraine-bench
  (cd "$work" && "$bin" --only a,w,b,c,l,u,q,m,det --reps 1 --threads 1,2 --det-steps 300 \
     --json "$work/$side.json" >"$work/$side-bench.txt" 2>&1)
done
"$py" - "$work/old.json" "$work/new.json" <<'PY' || status=1
import json, sys
def hashes(p):
    doc = json.load(open(p))
    rows = doc["runs"]
    return {(r["problem"], r["threads"]): r["state_hash"] for r in rows if "state_hash" in r}
old, new = hashes(sys.argv[1]), hashes(sys.argv[2])
# an older bench hashes only its determinism problems: compare what both hash
both = sorted(set(old) & set(new))
bad = [k for k in both if new[k] != old[k]]
for k in bad: print("  %s on %d thread(s): %s -> %s" % (k[0], k[1], old[k], new[k]))
print("bitwise: %d bench hashes compared, %d differ" % (len(both), len(bad)))
sys.exit(1 if bad or not both or not set(old) <= set(new) else 0)
PY

echo "bitwise: decks"
for side in old new; do
  bin=$([ $side = old ] && echo "$work/old-build" || echo "$root/build-bitwise")/moraine
  mkdir -p "$work/$side-ck"
  for deck in "$here"/*.lua; do
    "$bin" "$deck" --set out="$work/$side-ck" --set decks="$root/tests/decks" -o "$work/$side-ck/run" \
      >"$work/$side-ck/$(basename "$deck" .lua).log" 2>&1 || { echo "  $deck failed with $side"; status=1; }
  done
done
"$py" "$here/compare.py" "$work/old-ck" "$work/new-ck" || status=1
echo "bitwise: outputs in $work"
exit $status
