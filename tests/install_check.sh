#!/usr/bin/env bash
# moraine: an installed tree finds its pure-Lua library without any
# environment variable. usage: install_check.sh BUILD_DIR PREFIX
set -eu
build=$1 prefix=$2
rm -rf "$prefix"
cmake --install "$build" --prefix "$prefix" > /dev/null
deck=$(mktemp --suffix=.lua)
trap 'rm -f "$deck"' EXIT
cat > "$deck" <<'LUA'
local m = require "moraine"
assert(m == mpm, "require 'moraine' and the global mpm are the same module")
assert(type(mpm.dt.fixed) == "function", "the pure-Lua helpers are loaded")
print(mpm.library_dir)
LUA
dir=$(cd /tmp && "$prefix/bin/moraine" "$deck" -q -o "$prefix/out")
case "$(realpath "$dir")" in
  "$(realpath "$prefix")"/*) echo "library found in the installed tree: $dir"; echo "1 passed, 0 failed" ;;
  *) echo "FAIL: library taken from $dir, not from $prefix"; echo "0 passed, 1 failed"; exit 1 ;;
esac
