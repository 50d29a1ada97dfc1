#!/usr/bin/env bash
# moraine: set up, build and run the default example deck (the README's main job).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMORAINE_NATIVE=ON
cmake --build build -j "$(nproc 2>/dev/null || echo 2)"
# the script's own outputs: a second run replaces those of the first
build/moraine examples/colliding_disks/deck.lua -o out/colliding_disks --overwrite "$@"
