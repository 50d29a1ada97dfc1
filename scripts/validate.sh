#!/usr/bin/env bash
# moraine: the long validation runs, outside the quick test command.
#
#   scripts/validate.sh [OUTDIR]     (default: out/validate)
#
# Runs the full-length versions of the verification cases, keeps each run's
# printed figures in OUTDIR/<case>.txt, and draws the comparison plots into
# doc/figures/. About 15 minutes on a 2-core machine. The quick versions of
# the same cases run (and assert) in scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/validate}
mkdir -p "$out" doc/figures
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j "$(nproc 2>/dev/null || echo 2)" > /dev/null
moraine=build/moraine
plot=scripts/moraine-plot

run() { # run NAME DECK [--set ...]: figures to OUTDIR/NAME.txt
  local name=$1 deck=$2
  shift 2
  echo "== $name"
  "$moraine" "$deck" -q -o "$out/$name" "$@" | tee "$out/$name.txt"
}

# merge COLUMN of several CSVs (same rows, e.g. the same fixed dt) into one CSV
# with a column per file: merge OUT COLUMN LABEL=FILE ...
merge() {
  local dest=$1 column=$2
  shift 2
  /usr/bin/python3 - "$dest" "$column" "$@" <<'PY'
import csv, sys
dest, column, pairs = sys.argv[1], sys.argv[2], [a.split("=", 1) for a in sys.argv[3:]]
series = {}
for label, path in pairs:
    with open(path) as f:
        series[label] = {float(r["time"]): r[column] for r in csv.DictReader(f)}
times = sorted(set.intersection(*[set(s) for s in series.values()]))
with open(dest, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["time"] + [label for label, _ in pairs])
    for t in times:
        w.writerow([repr(t)] + [series[label][t] for label, _ in pairs])
PY
}

# Bouncing cube, every strategy with USF, three seconds (000 Fig. 3)
strategies="PIC FLIP APIC AFLIP TPIC TFLIP XPIC(2) XPIC(4)"
run bouncing_cube tests/decks/bouncing_cube_strategies.lua --set time=3 \
    --set "strategies=$(echo $strategies | tr ' ' ',')"
pairs=()
for s in $strategies; do pairs+=("$s=$out/bouncing_cube/cube_${s//[()]/}.csv"); done
merge "$out/bouncing_cube_energy.csv" E_total "${pairs[@]}"
$plot doc/figures/bouncing_cube_energy.png "$out/bouncing_cube_energy.csv" $strategies \
    --title "Bouncing cube (000 §4.1): total energy, USF, a_tau = 0.05" --ylabel "E_total (J)"

# Rotating cube, 100 s (000 §4.2)
run rotating_cube tests/decks/rotating_cube.lua --set time=100
pairs=()
for s in APIC AFLIP TFLIP; do pairs+=("$s=$out/rotating_cube/cube_$s.csv"); done
merge "$out/rotating_cube_L.csv" L_centroid "${pairs[@]}"
$plot doc/figures/rotating_cube_L.png "$out/rotating_cube_L.csv" APIC AFLIP TFLIP \
    --title "Rotating cube (000 §4.2): angular momentum about the centroid" --ylabel "L (kg m^2/s)"

# The other cases at full length, where their decks offer it
for deck in tests/decks/*.lua; do
  name=$(basename "$deck" .lua)
  if grep -q 'mpm.param("full"' "$deck"; then run "$name" "$deck" --set full=true; fi
done
echo "validation runs in $out, figures in doc/figures"
