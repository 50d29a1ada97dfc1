#!/usr/bin/env bash
# moraine: rerun every verification case and regenerate the validation report.
#
#   scripts/validate.sh [OUTDIR]     (default: out/validate)
#
# Builds build/ (Release), then scripts/validation/report.py runs every case of
# scripts/validation/cases.toml at full length (each run's output in
# OUTDIR/<case>.log) and rewrites doc/validation.md and doc/figures/ from the
# RESULT lines the runs print. The same as `cmake --build build --target
# validate`. About half an hour on a 2-core machine; the quick versions of the
# cases run (and assert) in scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/validate}
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j "$(nproc 2>/dev/null || echo 2)" > /dev/null
exec "${PYTHON:-python3}" scripts/validation/report.py --moraine build/moraine --build build --out "$out"
