# Shared by example1.sh … example5.sh: the testbed binary and the output directory.
#   TESTBED   the binary (default: built and run by cargo, release profile)
#   DATA      the octahedron mesh (default: data/octa.m of this repository)
#   $1        the output directory (default: results/examples/)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
if [ -z "${TESTBED:-}" ]; then
    cargo build -q --release -p testbed --manifest-path "$ROOT/Cargo.toml"
    TESTBED="${CARGO_TARGET_DIR:-$ROOT/target}/release/testbed"
fi
DATA="${DATA:-$ROOT/data/octa.m}"
OUT="${1:-$ROOT/results/examples}"
mkdir -p "$OUT"
tb() { "$TESTBED" "$@"; }
