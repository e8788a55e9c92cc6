#!/usr/bin/env bash
# Rewrites every committed result directory with the command its report documents (release
# build). `scripts/results.sh ring curve` reruns only those; with no argument, all of them.
# Each study stages its directory and swaps it in whole, so an interrupted run leaves the
# previous results.
#
# `scripts/results.sh --quick [STUDY…]` (what scripts/run-quick runs in CI) never touches
# results/: it runs the same commands with the debug build (no release build) into a temporary
# directory and fails unless every report equals the committed one apart from its timings (see
# `compare` below; the example pictures byte for byte). Without STUDY it runs all but `realmesh`
# (about a minute in a debug build; `--quick realmesh` runs it).
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
if [ "${1:-}" = "--quick" ]; then
  quick=1
  shift
fi
all=(ring curve interior schemes solvers sweep estimation realmesh franke examples)
if [ "$quick" = 1 ]; then
  default=(ring curve interior schemes solvers sweep estimation franke examples)
  # scripts/run-quick passes the binaries CI's `cargo test --workspace` just built (a build
  # here, with other features, would compile the workspace again); by hand, the debug build.
  if [ -z "${EXPERIMENTS:-}" ] || [ -z "${TESTBED:-}" ]; then
    cargo build -q -p experiments -p testbed
    EXPERIMENTS="${CARGO_TARGET_DIR:-target}/debug/experiments"
    TESTBED="${CARGO_TARGET_DIR:-target}/debug/testbed"
  fi
  OUT="$(mktemp -d)"
  trap 'rm -rf "$OUT"' EXIT
else
  default=("${all[@]}")
  cargo build -q --release -p experiments -p testbed
  EXPERIMENTS="${CARGO_TARGET_DIR:-target}/release/experiments"
  TESTBED="${CARGO_TARGET_DIR:-target}/release/testbed"
fi
E="$EXPERIMENTS"
run() { echo "== $*" >&2; "$@"; }
# Where a study writes: its committed directory, or in quick mode the same name under $OUT.
# `o DIR` gives the `--output` option a study needs for that (none in a full run of a study
# whose committed command has none, so that its report's command line stays as committed).
dir() { if [ "$quick" = 1 ]; then echo "$OUT/$1"; else echo "results/$1"; fi; }
o() { if [ "$quick" = 1 ]; then echo "--output $OUT/$1"; fi; }
# compare DIR FILE…: each quick-mode FILE of DIR against results/DIR/FILE. JSON (a report, or
# JSON Lines) must have the same keys, lengths, strings and integers, and floats within
# REL_TOL relative (absolute below 1); keys naming a time (`time`, `seconds`) are skipped: they
# are the machine's. The debug build computes the release build's numbers (Rust does not
# reassociate floating point: measured equal apart from the timings on every study), so 1e-9
# only leaves room for a summation order. Other files (pictures) must be equal byte for byte.
compare() {
  python3 - "$OUT" "$@" <<'EOF'
import json, re, sys
from pathlib import Path

REL_TOL = 1e-9
TIMING = re.compile(r"time|seconds")
out, study, files = Path(sys.argv[1]), sys.argv[2], sys.argv[3:]
diffs = []


def walk(a, b, path):
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            diffs.append(f"{path}: keys {sorted(set(a) ^ set(b))} in only one")
        for k in sorted(set(a) & set(b)):
            if not TIMING.search(k):
                walk(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            diffs.append(f"{path}: {len(a)} items committed, {len(b)} now")
        for i, (x, y) in enumerate(zip(a, b)):
            walk(x, y, f"{path}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        if not (isinstance(a, (int, float)) and isinstance(b, (int, float))
                and abs(a - b) <= REL_TOL * max(1.0, abs(a))):
            diffs.append(f"{path}: committed {a!r}, now {b!r}")
    elif a != b:
        diffs.append(f"{path}: committed {str(a)[:80]!r}, now {str(b)[:80]!r}")


for name in files:
    committed, now = Path("results") / study / name, out / study / name
    if name.endswith(".json"):
        walk(json.loads(committed.read_text()), json.loads(now.read_text()), name)
    elif name.endswith(".jsonl"):
        a, b = committed.read_text().splitlines(), now.read_text().splitlines()
        walk([json.loads(x) for x in a], [json.loads(x) for x in b], name)
    elif committed.read_bytes() != now.read_bytes():
        diffs.append(f"{name}: differs from the committed file")
for d in diffs[:20]:
    print(f"results.sh --quick: results/{study}/{d}", file=sys.stderr)
if diffs:
    sys.exit(f"results.sh --quick: {study}: {len(diffs)} differences from results/{study}/ "
             f"(rerun `scripts/results.sh {study}` and commit, or find what changed)")
print(f"results.sh --quick: {study}: {', '.join(files)} as committed", file=sys.stderr)
EOF
}
check() { if [ "$quick" = 1 ]; then compare "$@"; fi; }
for study in "${@:-${default[@]}}"; do
  case "$study" in
    ring) run $E ring $(o ring) > /dev/null; check ring report.json ;;
    curve) mkdir -p "$(dir curve)"
      run $E curve --input data/curve-problems.jsonl --output "$(dir curve)/curves.jsonl" \
        --curves chord,dbhs,optimized --dbhs-pick closest --solver exact-penalty --plot "$(dir curve)"
      check curve curves.jsonl report.json ;;
    interior) run $E interior $(o interior); check interior report.json ;;
    schemes) run $E schemes --curves optimized --solver exact-penalty --face-segments 8 \
        --output "$(dir schemes)"; check schemes report.json ;;
    solvers) run $E solvers --data ring,sphere,capsule,octa --output "$(dir solvers)"
      check solvers report.json ;;
    sweep)
      run $E sweep $(o sweep)
      run $E sweep --scheme nielson --output "$(dir sweep-nielson)"
      run $E sweep --scheme loop --output "$(dir sweep-loop)"
      check sweep report.json; check sweep-nielson report.json; check sweep-loop report.json ;;
    estimation) run $E estimation $(o estimation); check estimation report.json ;;
    realmesh) run $E realmesh $(o realmesh); check realmesh report.json ;;
    franke) run $E franke $(o franke); check franke report.json ;;
    examples)
      # Every examples/example*.sh; in quick mode their pictures must be results/examples/'s
      # pictures, the same names (a new example needs its committed picture) and bytes.
      for script in examples/example*.sh; do
        if [ "$quick" = 1 ]; then
          TESTBED="$TESTBED" run bash "$script" "$(dir examples)"
        else
          TESTBED="$TESTBED" run bash "$script"
        fi
      done
      if [ "$quick" = 1 ]; then
        made="$(cd "$(dir examples)" && ls)"
        committed="$(cd results/examples && ls | grep -v '^README.md$')"
        if [ "$made" != "$committed" ]; then
          echo "results.sh --quick: examples wrote [$(echo $made)], results/examples/ holds [$(echo $committed)]" >&2
          exit 1
        fi
        check examples $made
      fi ;;
    *) echo "unknown study: $study (known: ${all[*]})" >&2; exit 2 ;;
  esac
done
