#!/usr/bin/env bash
# Runs every fuzz target for a while, keeps and minimises the corpus, and prints a summary.
#
#   fuzz/nightly.sh [SECONDS_PER_TARGET] [TARGET...]      (default: 600 s, every target)
#
# Each target starts from its working corpus (fuzz/corpus/T, kept between runs, not committed),
# the committed seeds (fuzz/seeds/T) and reproducers (fuzz/regressions/T). New inputs go to the
# working corpus, which `cargo fuzz cmin` then minimises. Crashes land in fuzz/artifacts/T.
#
# Nightly Rust gives the default AddressSanitizer build; without nightly the targets build on
# stable with `-s none` (full coverage guidance, no sanitizer: refrast forbids unsafe code, so its
# bugs are panics, overflows and hangs, which need none). cargo-fuzz is installed if missing.
#
# Environment: FUZZ_TIMEOUT (s per input before libFuzzer calls it a hang, default 60),
# FUZZ_RSS_MB (memory limit, default 2048), FUZZ_SKIP_CMIN=1 (keep the corpus as it grew),
# FUZZ_TRACE_COMPARES=1 (libFuzzer's comparison tracing back on; off by default, fuzz/args.sh),
# FUZZ_UPDATE_SEEDS=1 (replace fuzz/seeds/T by the fewest inputs of corpus and seeds that keep
# their coverage, libFuzzer's -set_cover_merge; review and commit them).
# Exit: 0 no crash; 1 a target crashed or hung; 2 bad usage or cargo-fuzz cannot be installed;
# 3 the targets do not build, on nightly or stable.
set -uo pipefail
cd "$(dirname "$0")"

# shellcheck source=fuzz/args.sh
source ./args.sh
parse_fuzz_args fuzz/nightly.sh 600 "$@"

if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "== installing cargo-fuzz (cargo install cargo-fuzz --locked)"
  if ! cargo install cargo-fuzz --locked; then
    echo "fuzz/nightly.sh: cannot install cargo-fuzz; nothing was fuzzed" >&2
    exit 2
  fi
fi
# The sanitizer build needs nightly; stable builds the same targets with -s none.
build() {
  for t in "${targets[@]}"; do
    "${fuzz[@]}" build "${sanitizer[@]}" "${instrument[@]}" "$t" || return 1
  done
}
built=0
if cargo +nightly --version >/dev/null 2>&1; then
  fuzz=(cargo +nightly fuzz)
  sanitizer=(-s address)
  echo "== building ${targets[*]} with nightly Rust and AddressSanitizer"
  build && built=1
  ((built)) || echo "== the nightly build failed; trying stable with -s none"
else
  echo "== no nightly Rust (cargo +nightly): building on stable with -s none (coverage guided, no sanitizer)"
fi
if ((!built)); then
  fuzz=(cargo fuzz)
  sanitizer=(-s none)
  if ! build; then
    echo "fuzz/nightly.sh: the fuzz targets do not build (see the errors above); nothing was fuzzed" >&2
    exit 3
  fi
fi

logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
summary=()
crashed=0
# One libFuzzer statistic from a -print_final_stats log.
stat() { awk -v k="stat::$1:" '$1 == k { print $2 }' "$2" | tail -n 1; }
count() { find "$1" -maxdepth 1 -type f 2>/dev/null | wc -l; }
# Crash, hang and out-of-memory reproducers (libFuzzer also leaves slow-unit-* files there).
failures() { find "$1" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'timeout-*' -o -name 'oom-*' -o -name 'leak-*' \) | wc -l; }

# Where a target's committed seeds are: `fast` decodes its input as `differential` does.
seeds_of() { if [[ $1 == fast ]]; then echo seeds/differential; else echo "seeds/$1"; fi; }

for t in "${targets[@]}"; do
  seeds=$(seeds_of "$t")
  mkdir -p "corpus/$t" "$seeds" "regressions/$t" "artifacts/$t"
  before_artifacts=$(failures "artifacts/$t")
  echo "== fuzzing $t for ${seconds} s (corpus: $(count "corpus/$t") kept, $(count "$seeds") seeds, $(count "regressions/$t") reproducers)"
  log="$logs/$t.log"
  "${fuzz[@]}" run "${sanitizer[@]}" "${instrument[@]}" "$t" "corpus/$t" "$seeds" "regressions/$t" -- \
    -max_total_time="$seconds" -timeout="${FUZZ_TIMEOUT:-60}" -rss_limit_mb="${FUZZ_RSS_MB:-2048}" \
    -print_final_stats=1 >"$log" 2>&1
  status=$?
  tail -n 3 "$log" | sed 's/^/   /'
  grown=$(count "corpus/$t")
  if [[ ${FUZZ_SKIP_CMIN:-0} != 1 ]] && ((grown > 0)); then
    "${fuzz[@]}" cmin "${sanitizer[@]}" "${instrument[@]}" "$t" "corpus/$t" -- -timeout="${FUZZ_TIMEOUT:-60}" >"$logs/$t.cmin" 2>&1 ||
      echo "   cmin failed for $t (corpus kept as it grew); see its log above" >&2
  fi
  if [[ ${FUZZ_UPDATE_SEEDS:-0} == 1 && $seeds != "seeds/$t" ]]; then
    echo "   $t shares $seeds with another target: left as it was"
  elif [[ ${FUZZ_UPDATE_SEEDS:-0} == 1 ]]; then
    fresh=$(mktemp -d)
    if "${fuzz[@]}" run "${sanitizer[@]}" "${instrument[@]}" "$t" "$fresh" "corpus/$t" "seeds/$t" -- -set_cover_merge=1 \
      -timeout="${FUZZ_TIMEOUT:-60}" >"$logs/$t.seeds" 2>&1; then
      rm -f "seeds/$t"/* && mv "$fresh"/* "seeds/$t"/ 2>/dev/null
      echo "   seeds/$t now holds $(count "seeds/$t") inputs"
    else
      echo "   updating seeds/$t failed; left as it was" >&2
    fi
    rm -rf "$fresh"
  fi
  crashes=$(($(failures "artifacts/$t") - before_artifacts))
  if ((status != 0)) && ((crashes == 0)); then
    # libFuzzer stopped on its own (an out-of-memory or a hang writes an artifact; this did not).
    echo "   $t exited with status $status; the last lines of its log:" >&2
    tail -n 20 "$log" | sed 's/^/   /' >&2
    crashes=1
  fi
  ((crashes > 0)) && crashed=1
  execs=$(stat number_of_executed_units "$log")
  rate=$(stat average_exec_per_sec "$log")
  summary+=("$(printf '%-13s %8s s %12s %10s %9s %9s %8s' "$t" "$seconds" "${execs:-?}" "${rate:-?}" \
    "$grown" "$(count "corpus/$t")" "$crashes")")
done

echo
echo "== summary ($(date -u +%Y-%m-%dT%H:%MZ), ${fuzz[*]} ${sanitizer[*]})"
printf '%-13s %10s %12s %10s %9s %9s %8s\n' target time executions exec/s corpus minimised crashes
printf '%s\n' "${summary[@]}"
echo "(corpus: fuzz/corpus/<target> after the run, before and after cmin; seeds and reproducers not counted)"
if ((crashed)); then
  echo "crashes are in fuzz/artifacts/<target>/; reproduce with: cargo fuzz run <target> <file>" >&2
  echo "then copy the file to fuzz/regressions/<target>/<what-it-shows> so that cargo test replays it" >&2
fi
exit "$crashed"
