#!/usr/bin/env bash
# End to end against a native reference (issue 28): a bare ring OBJ of about 10⁶ faces to
# patches (`experiments fit --data ring.obj --curves optimized --output ring.bzp`), timed N
# times, against N runs of solver/examples/lm_reference.rs (10⁶ hand-written two-parameter
# Levenberg–Marquardt solves). Prints each run's wall time, the medians, the ratio
# fit / reference (the issue's target: ≤ 12) and the fit's own stage times from its last run.
#
#   scripts/end_to_end.sh [--runs N] [--resolution R] [--quick]
#
# Builds nothing when the binaries exist: EXPERIMENTS (default target/release/experiments) and
# LM_REFERENCE (default target/release/examples/lm_reference); build them first with
#   cargo build --release -p experiments
#   cargo build --release -p solver --example lm_reference
#
# --quick (scripts/run-quick, seconds): the debug binaries (EXPERIMENTS as run-quick exports it;
# LM_REFERENCE defaults to ${CARGO_TARGET_DIR:-target}/debug/examples/lm_reference, which
# `cargo test --workspace` builds, and is built here only when missing), a ring of resolution
# 40, one run each, the reference at --count 10000. It fails (exit 1) unless both programs exit
# 0, `convert` reports a face count, the reference prints a finite checksum and the ratio is a
# finite positive number. The debug ratio says nothing about performance.
set -euo pipefail
cd "$(dirname "$0")/.."

quick=0
runs=3
# Resolution 1000 gives 10⁶ faces (`convert` reports the count; checked below).
resolution=1000
count=1000000
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --runs) runs="$2"; shift ;;
    --resolution) resolution="$2"; shift ;;
    -h | --help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "end_to_end: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done

if [ "$quick" = 1 ]; then
  runs=1
  resolution=40
  count=10000
  EXPERIMENTS="${EXPERIMENTS:-${CARGO_TARGET_DIR:-target}/debug/experiments}"
  LM_REFERENCE="${LM_REFERENCE:-${CARGO_TARGET_DIR:-target}/debug/examples/lm_reference}"
  if [ ! -x "$LM_REFERENCE" ]; then
    cargo build -q -p solver --example lm_reference
  fi
else
  EXPERIMENTS="${EXPERIMENTS:-target/release/experiments}"
  LM_REFERENCE="${LM_REFERENCE:-target/release/examples/lm_reference}"
fi
for bin in "$EXPERIMENTS" "$LM_REFERENCE"; do
  if [ ! -x "$bin" ]; then
    echo "end_to_end: $bin is missing: build it first (see the header of $0)" >&2
    exit 1
  fi
done

dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# Wall seconds of one command, its output in $dir/out; nonzero exit fails the script.
timed() {
  local t0 t1
  t0=$(date +%s%N)
  if ! "$@" > "$dir/out" 2>&1; then
    echo "end_to_end: failed: $*" >&2
    tail -n 20 "$dir/out" >&2
    exit 1
  fi
  t1=$(date +%s%N)
  awk -v ns=$((t1 - t0)) 'BEGIN { printf "%.3f", ns / 1e9 }'
}

# The median of the arguments.
median() { printf '%s\n' "$@" | LC_ALL=C sort -g | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else printf "%.3f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

"$EXPERIMENTS" convert --data ring --resolution "$resolution" --output "$dir/ring.obj" > "$dir/convert" 2>&1 || {
  cat "$dir/convert" >&2
  echo "end_to_end: convert failed" >&2
  exit 1
}
faces=$(sed -n 's/.* vertices, \([0-9]*\) faces).*/\1/p' "$dir/convert" | head -n 1)
if [ -z "$faces" ]; then
  cat "$dir/convert" >&2
  echo "end_to_end: convert reported no face count" >&2
  exit 1
fi
echo "mesh: ring, resolution $resolution: $faces faces ($(wc -c < "$dir/ring.obj") bytes of OBJ)"

fit_times=()
for _ in $(seq "$runs"); do
  rm -f "$dir/ring.bzp"
  t=$(timed "$EXPERIMENTS" fit --data "$dir/ring.obj" --curves optimized --output "$dir/ring.bzp")
  fit_times+=("$t")
  echo "fit: $t s"
done
[ -s "$dir/ring.bzp" ] || { echo "end_to_end: fit wrote no $dir/ring.bzp" >&2; exit 1; }
stages=$(grep -E 'time:|streamed:' "$dir/out" || true)

ref_times=()
for _ in $(seq "$runs"); do
  t=$(timed "$LM_REFERENCE" --count "$count")
  ref_times+=("$t")
  checksum=$(sed -n 's/^checksum //p' "$dir/out")
  inner=$(sed -n 's/^seconds //p' "$dir/out")
  echo "reference: $t s (its own loop $inner s, checksum $checksum)"
done
finite='^-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?$'
[[ "$checksum" =~ $finite ]] || { echo "end_to_end: the reference's checksum is not finite: $checksum" >&2; exit 1; }

fit_median=$(median "${fit_times[@]}")
ref_median=$(median "${ref_times[@]}")
ratio=$(awk -v f="$fit_median" -v r="$ref_median" 'BEGIN { if (r > 0) printf "%.2f", f / r; else print "nan" }')
echo "fit's stages (last run):"
echo "$stages"
echo "median of $runs: fit $fit_median s, reference ($count solves) $ref_median s, ratio $ratio (target ≤ 12)"
echo "load: $(uptime)"
if ! awk -v x="$ratio" 'BEGIN { exit !(x + 0 > 0 && x != "nan") }'; then
  echo "end_to_end: the ratio $ratio is not a finite positive number" >&2
  exit 1
fi
