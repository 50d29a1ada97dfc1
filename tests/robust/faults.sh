#!/usr/bin/env bash
# moraine robustness: every output file fails once, with ENOSPC and with EIO,
# at open, write, flush, close and rename (tests/robust/faults.py runs the
# cases with the LD_PRELOAD library tests/robust/faultfs.c; the sites are
# listed in doc/robustness.md, "Fault injection"). The message shown is the
# case of Ctrl-C on a full disk: the interrupted checkpoint cannot be written.
# case: disk full | every output file fails once (ENOSPC, EIO at open, write, flush, close, rename); shown: SIGINT on a full disk
# expect: run\{\}: interrupted by signal 2 after step 25 .*; the state at step 25 could not be saved: cannot write '.*/resumed_interrupted\.h5': No space left on device
# usage: faults.sh MORAINE OUTDIR PYTHON
exec "$3" "$(dirname "$0")/faults.py" "$1" "$2"
