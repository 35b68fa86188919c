#!/usr/bin/env bash
# Executions per second of every fuzz target (or those named), on one core, without a
# sanitizer (-s none), from the committed seeds and reproducers with a fixed libFuzzer seed: a
# measure of the oracles' and implementations' speed that is comparable from run to run.
#
#   fuzz/rate.sh [SECONDS] [TARGET...]      (default: 10 s a target, every target)
#
# Each target runs for SECONDS (-max_total_time, -seed=1, so the same inputs in the same
# order) into a scratch corpus, pinned to CPU 0 (taskset, when present), with comparison tracing
# as fuzz/nightly.sh has it (FUZZ_TRACE_COMPARES, fuzz/args.sh); nothing is written to
# fuzz/corpus or fuzz/seeds. Prints a table: target, executions, exec/s (libFuzzer's average). Exit 2 on bad usage or without cargo-fuzz, 3 when the
# targets do not build.
set -uo pipefail
cd "$(dirname "$0")"

# shellcheck source=fuzz/args.sh
source ./args.sh
parse_fuzz_args fuzz/rate.sh 10 "$@"
if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "fuzz/rate.sh: cargo-fuzz is missing (cargo install cargo-fuzz --locked)" >&2
  exit 2
fi
for t in "${targets[@]}"; do
  cargo fuzz build -s none "${instrument[@]}" "$t" >/dev/null 2>&1 || {
    echo "fuzz/rate.sh: $t does not build (cargo fuzz build -s none ${instrument[*]} $t)" >&2
    exit 3
  }
done
pin=()
command -v taskset >/dev/null && pin=(taskset -c 0)
seeds_of() { if [[ $1 == fast ]]; then echo seeds/differential; else echo "seeds/$1"; fi; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
printf '%-13s %10s %9s\n' target executions exec/s
for t in "${targets[@]}"; do
  mkdir -p "$scratch/$t" "regressions/$t"
  log="$scratch/$t.log"
  "${pin[@]}" cargo fuzz run -s none "${instrument[@]}" "$t" "$scratch/$t" "$(seeds_of "$t")" "regressions/$t" -- \
    -max_total_time="$seconds" -seed=1 -print_final_stats=1 >"$log" 2>&1
  status=$?
  execs=$(awk '$1 == "stat::number_of_executed_units:" { print $2 }' "$log" | tail -n 1)
  rate=$(awk '$1 == "stat::average_exec_per_sec:" { print $2 }' "$log" | tail -n 1)
  printf '%-13s %10s %9s\n' "$t" "${execs:-?}" "${rate:-?}"
  ((status == 0)) || { echo "  $t exited with $status; its log ends:" >&2; tail -n 5 "$log" >&2; }
done
