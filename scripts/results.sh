#!/usr/bin/env bash
# Rewrites every committed result directory with the command its report documents (release
# build). `scripts/results.sh ring curve` reruns only those; with no argument, all of them.
# Each study stages its directory and swaps it in whole, so an interrupted run leaves the
# previous results.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build -q --release -p experiments -p testbed
E=./target/release/experiments
run() { echo "== $*" >&2; "$@"; }
all=(ring curve interior schemes solvers sweep estimation realmesh franke examples)
for study in "${@:-${all[@]}}"; do
  case "$study" in
    ring) run $E ring > /dev/null ;;
    curve) run $E curve --input data/curve-problems.jsonl --output results/curve/curves.jsonl \
        --curves chord,dbhs,optimized --dbhs-pick closest --solver exact-penalty --plot results/curve ;;
    interior) run $E interior ;;
    schemes) run $E schemes --curves optimized --solver exact-penalty --face-segments 8 \
        --output results/schemes ;;
    solvers) run $E solvers --data ring,sphere,capsule,octa --output results/solvers ;;
    sweep)
      run $E sweep
      run $E sweep --scheme nielson --output results/sweep-nielson
      run $E sweep --scheme loop --output results/sweep-loop ;;
    estimation) run $E estimation ;;
    realmesh) run $E realmesh ;;
    franke) run $E franke ;;
    examples)
      for n in 1 2 3 4 5; do
        TESTBED=./target/release/testbed run bash "examples/example$n.sh"
      done ;;
    *) echo "unknown study: $study (known: ${all[*]})" >&2; exit 2 ;;
  esac
done
