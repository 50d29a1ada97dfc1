#!/usr/bin/env bash
# moraine: run one libFuzzer harness (tests/fuzz/README.md).
#
#   tests/fuzz/run.sh BUILD_DIR HARNESS SECONDS [WORK_DIR]
#
# BUILD_DIR was configured with -DMORAINE_FUZZ=ON (clang); HARNESS is
# checkpoint or deck. New inputs go to WORK_DIR/corpus-HARNESS (default
# fuzz-work/ in the current directory) on top of the seed corpus
# tests/fuzz/corpus/HARNESS; a crash, leak or sanitizer report stops the run
# and leaves its input as WORK_DIR/HARNESS-crash-* (or -leak-, -timeout-, -oom-).
# The last lines of the log give stat::number_of_executed_units.
set -euo pipefail
build=$1 harness=$2 seconds=$3 work=${4:-fuzz-work}
here=$(cd "$(dirname "$0")" && pwd)
case $harness in
  checkpoint) max_len=20000 ;;   # the seed checkpoint is about 16 kB
  deck) max_len=4096 ;;          # the harness ignores longer inputs
  *) echo "run.sh: unknown harness '$harness' (checkpoint or deck)" >&2; exit 2 ;;
esac
mkdir -p "$work/corpus-$harness"
export LSAN_OPTIONS=suppressions=$here/lsan.supp
exec "$build/tests/fuzz_$harness" -max_total_time="$seconds" -max_len=$max_len -rss_limit_mb=3072 -timeout=60 \
  -print_final_stats=1 -artifact_prefix="$work/$harness-" "$work/corpus-$harness" "$here/corpus/$harness"
