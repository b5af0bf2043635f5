#!/usr/bin/env bash
# Explores new random inputs for the property tests: the test command (scripts/test.sh) draws them
# from one fixed seed so that its answer never changes by chance; this script runs the crates that
# hold property tests with fresh seeds, round after round, and names the seed of any failure
# (re-run it with PROPTEST_RNG_SEED=<seed> cargo test ... and keep the case in the test).
# Run it before every stop, beside nothing else. Usage: scripts/test-explore.sh [rounds] (3).
set -euo pipefail
cd "$(dirname "$0")/.."
rounds="${1:-3}"
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  export XDG_RUNTIME_DIR="$(mktemp -d)"
  chmod 700 "$XDG_RUNTIME_DIR"
fi
packages=(-p cnets-geometry -p cnets-engine -p cnets-nodes -p cnets -p cnets-tests)
cargo test "${packages[@]}" --no-run -q
for round in $(seq 1 "$rounds"); do
  seed="$(od -An -N8 -tu8 /dev/urandom | tr -d ' ')"
  echo "== round $round of $rounds: PROPTEST_RNG_SEED=$seed"
  if ! PROPTEST_RNG_SEED="$seed" cargo test "${packages[@]}" -q >target/test-explore.log 2>&1; then
    grep -E "^test .*FAILED|panicked|minimal failing input" target/test-explore.log >&2 || true
    echo "test-explore.sh: round $round failed with PROPTEST_RNG_SEED=$seed (target/test-explore.log)" >&2
    exit 1
  fi
  grep -E "^test result:" target/test-explore.log | awk '{p+=$4} END {print "   passed:", p}'
done
echo "test-explore.sh: $rounds rounds passed"
