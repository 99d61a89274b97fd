#!/usr/bin/env bash
# Instructions per env step, counted by valgrind's callgrind (repeatable on a busy VM,
# unlike wall-clock rates): runs tools/step_count twice (N and 2N steps) and prints
# (Ir(2N) - Ir(N)) / N, which cancels model compilation and start-up.
#   scripts/instructions_per_step.sh [TASK] [LAYER: raw|gym|physics] [N] [ROBOT] [CONTROLLER]
# (ROBOT: another robot than the Panda, `-` for the Panda; CONTROLLER: an arm controller
# type, configured by robosuite's part config file for it.)
set -euo pipefail
cd "$(dirname "$0")/.."
task=${1:-Lift}
layer=${2:-gym}
n=${3:-100}
extra=("${@:4}")
command -v valgrind > /dev/null || { echo "needs valgrind (apt-get install valgrind)" >&2; exit 1; }
cargo build --release -q -p tools --bin step_count
bin=target/release/step_count
out=$(mktemp -d)
count() {
    valgrind --tool=callgrind --callgrind-out-file="$out/cg.$1" "$bin" "$task" "$layer" "$1" "${extra[@]}" \
        2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
a=$(count "$n")
b=$(count $((2 * n)))
echo "$task ${extra[*]} $layer: $(( (b - a) / n )) instructions per env step (callgrind, $n vs $((2 * n)) steps; profiles in $out)"
