#!/usr/bin/env bash
# moraine: the installed tree serves C programs and a stock lua5.4
# (doc/c-api.md). usage: install_c_api.sh SOURCE_DIR BUILD_DIR WORK_DIR PYTHON
#  - `cmake --install` into a temporary prefix puts there the library, the
#    headers, moraine.pc, the CMake package and the man page;
#  - examples/c_api/drop.c compiles with `pkg-config --cflags --libs moraine`
#    and, as a tiny CMake project, with find_package(moraine) against that
#    tree alone, and both programs match the installed moraine's run of
#    examples/block_drop/deck.lua bit for bit (every snapshot, read with VTK,
#    and the lines both print);
#  - `lua5.4 -e 'require "moraine"'` works with LUA_CPATH into the prefix, and
#    a tiny deck runs through stock lua5.4.
set -u
src=$1 build=$2 work=$3 python=$4
prefix=$work/prefix time=0.3
rm -rf "$work" && mkdir -p "$work"
fail=0
check() { # MESSAGE COMMAND...: run it, fail with MESSAGE and its output if it fails
  local what=$1; shift
  if ! out=$("$@" 2>&1); then echo "FAIL: $what"; echo "$out" | tail -n 15; fail=1; return 1; fi
}
check "cmake --install" cmake --install "$build" --prefix "$prefix" || { echo "0 passed, 1 failed"; exit 1; }
for f in include/moraine/moraine.h lib/cmake/moraine/moraineConfigVersion.cmake share/man/man1/moraine.1 \
         share/moraine/lua/moraine/init.lua; do
  [ -f "$prefix/$f" ] || { echo "FAIL: $f not installed"; fail=1; }
done
grep -q 'output.*DIR' "$prefix/share/man/man1/moraine.1" || { echo "FAIL: the man page lacks --output"; fail=1; }
libdir=$(dirname "$(find "$prefix" -name 'libmoraine.so' | head -n 1)")
export PKG_CONFIG_PATH=$libdir/pkgconfig LD_LIBRARY_PATH=$libdir

# the deck, and the same problem from C, built two ways against the installed tree
"$prefix/bin/moraine" "$src/examples/block_drop/deck.lua" -q -o "$work/lua" --set time=$time > "$work/lua.txt" ||
  { echo "FAIL: the deck did not run"; fail=1; }
# shellcheck disable=SC2046 # the flags are words
check "cc drop.c \$(pkg-config --cflags --libs moraine)" \
  cc -std=c11 -Wall -Wextra -Werror "$src/examples/c_api/drop.c" -o "$work/drop" $(pkg-config --cflags --libs moraine)
mkdir -p "$work/project"
cat > "$work/project/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.18)
project(drop C)
find_package(moraine 0.1 REQUIRED)
add_executable(drop "$src/examples/c_api/drop.c")
target_link_libraries(drop PRIVATE moraine::moraine)
CMAKE
check "find_package(moraine) configures" cmake -S "$work/project" -B "$work/project/build" -DCMAKE_PREFIX_PATH="$prefix"
check "the find_package(moraine) project builds" cmake --build "$work/project/build"
for way in drop project/build/drop; do
  out=$work/c_$(basename "$(dirname "$way")")
  if ! "$work/$way" "$out" $time > "$out.txt" 2> "$out.err"; then
    echo "FAIL: $way did not run: $(cat "$out.err")"; fail=1; continue
  fi
  "$python" "$src/tests/python/compare_runs.py" "$work/lua" "$out" block || fail=1
  diff <(grep -E '^(block drop|[0-9.]+ s:)' "$work/lua.txt") <(grep -E '^(block drop|[0-9.]+ s:)' "$out.txt") ||
    { echo "FAIL: $way prints other figures than the deck"; fail=1; }
done

# the Lua C module in a stock lua5.4
export LUA_CPATH="$prefix/$(cd "$prefix" && find . -name moraine.so | sed 's|^\./||; s|moraine\.so$|?.so|')"
check "lua5.4 -e 'require \"moraine\"'" lua5.4 -e 'require "moraine"'
cat > "$work/tiny.lua" <<'LUA'
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, gravity = { 0, -9.81 },
                            thermo = 0, progress = false, output = { vtk = "tiny", every_steps = 5 } }
sim:add_particles(mpm.box{ min = { 0.3, 0.3 }, max = { 0.5, 0.5 } },
                  { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 } })
sim:run{ steps = 10 }
print(string.format("steps %d, t = %.6g s, %s", sim:step(), sim:time(), mpm.library_dir))
LUA
# run once: a second run into out/ would be refused as another run's outputs
if said=$(cd "$work" && lua5.4 tiny.lua 2>&1); then
  echo "$said" | grep -q "^steps 10, t = .*$prefix" || { echo "FAIL: lua5.4 tiny.lua said: $said"; fail=1; }
  [ -f "$work/out/tiny_000002.vtp" ] || { echo "FAIL: lua5.4 tiny.lua wrote no out/tiny_000002.vtp"; fail=1; }
else
  echo "FAIL: a deck through stock lua5.4"; echo "$said" | tail -n 15; fail=1
fi
if [ $fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi
exit $fail
