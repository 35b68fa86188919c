#!/usr/bin/env bash
# Every long job refrast has, one after another, each with its log, then one summary: the runs
# too long for each commit's CI (cargo test keeps a short form of each, docs/testing.md).
# Runnable by hand on this project's machines; the GitHub workflows
# (.github/workflows/*-nightly.yml) call it per job.
#
# Usage: scripts/nightly.sh [--out DIR] [--only JOB[,JOB...]] [--list]
#   --out DIR   where the logs and summary.txt go (default: nightly-out/, not committed)
#   --only      run only these jobs, in the order below
#   --list      print the jobs and what each runs, and exit
#
# Jobs (about 12 hours in all on 2 cores; each has its own time limit, below):
#   fuzz        every cargo-fuzz target for FUZZ_SECONDS (default 600) each (fuzz/nightly.sh)
#   drivers     lavapipe, llvmpipe, softpipe and SwiftShader at every rule's full cases, no time
#               budget, judged against expectations/*.txt (cargo test: 300 cases a rule)
#   seeds       every built-in at 20 seeds (scripts/certify_seeds.py --seeds 20)
#   scale       every built-in at the default seed with 10x the cases
#   restricted  the reference restricted to each setting's values, at full cases
#   mutants     cargo-mutants on the reference, then on the oracles (scripts/mutants.sh)
#   bench       fast's benchmark beside the baseline, lavapipe and SwiftShader
#               (scripts/bench_fast.py --json)
#
# Environment: FUZZ_SECONDS, MUTANTS_MINUTES (default 180 for the reference, and two thirds of
# it for the oracles), NIGHTLY_JOB_LIMIT (hours per job, default 6).
# Exit: 0 when every job run passed, 1 when one failed, 2 on bad usage.
set -uo pipefail
cd "$(dirname "$0")/.."

jobs_all=(fuzz drivers seeds scale restricted mutants bench)
out=nightly-out
only=""
list=0
while (($#)); do
  case $1 in
    --out) out=${2:?--out needs a folder}; shift 2 ;;
    --only) only=${2:?--only needs job names}; shift 2 ;;
    --list) list=1; shift ;;
    -h | --help) sed -n '2,25p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "scripts/nightly.sh: unknown argument '$1' (--help lists them)" >&2; exit 2 ;;
  esac
done
jobs=("${jobs_all[@]}")
if [[ -n $only ]]; then
  IFS=, read -r -a jobs <<<"$only"
  for j in "${jobs[@]}"; do
    if [[ " ${jobs_all[*]} " != *" $j "* ]]; then
      echo "scripts/nightly.sh: unknown job '$j'; the jobs are: ${jobs_all[*]}" >&2
      exit 2
    fi
  done
fi

refrast=${CARGO_TARGET_DIR:-target}/release/refrast
drivers=(lavapipe llvmpipe softpipe swiftshader)
# What each job runs (one command line each, for --list and the summary).
describe() {
  case $1 in
    fuzz) echo "fuzz/nightly.sh ${FUZZ_SECONDS:-600}" ;;
    drivers) echo "$refrast certify$(printf ' --impl %s' "${drivers[@]}")$(printf ' --expect expectations/%s.txt' "${drivers[@]}") --report $out/drivers --json $out/drivers.json --junit $out/drivers.xml" ;;
    seeds) echo "python3 scripts/certify_seeds.py --seeds 20 --refrast $refrast" ;;
    scale) echo "python3 scripts/certify_seeds.py --seeds 0 --scale 10 --refrast $refrast" ;;
    restricted) echo "$refrast certify --impl 'restricted:*' --report $out/restricted --json $out/restricted.json" ;;
    mutants) echo "scripts/mutants.sh ${MUTANTS_MINUTES:-180} && REFRAST_MUTATE=oracles scripts/mutants.sh $((${MUTANTS_MINUTES:-180} * 2 / 3))" ;;
    bench) echo "python3 scripts/bench_fast.py --json $out/bench.json" ;;
  esac
}
if ((list)); then
  for j in "${jobs[@]}"; do printf '%-11s %s\n' "$j" "$(describe "$j")"; done
  exit 0
fi

mkdir -p "$out"
summary="$out/summary.txt"
# Mesa's and SwiftShader's drivers want a private runtime folder.
if [[ -z ${XDG_RUNTIME_DIR:-} ]]; then
  export XDG_RUNTIME_DIR="$out/xdg"
  mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
fi
if [[ -f /usr/lib/chromium/vk_swiftshader_icd.json ]]; then
  export REFRAST_REQUIRE_SWIFTSHADER=1
fi
limit=$((${NIGHTLY_JOB_LIMIT:-6} * 3600))

{
  echo "refrast nightly: $(date -u +%Y-%m-%dT%H:%M:%SZ), $(git rev-parse --short HEAD 2>/dev/null || echo 'no git')"
  printf '%-11s %-8s %9s  %s\n' job result minutes log
} >"$summary"

echo "== building refrast (release)"
if ! cargo build --release -p refrast-cli >"$out/build.log" 2>&1; then
  tail -20 "$out/build.log"
  echo "build: FAILED (see $out/build.log)" | tee -a "$summary"
  exit 1
fi

failed=0
for j in "${jobs[@]}"; do
  log="$out/$j.log"
  command=$(describe "$j")
  echo "== $j: $command (log: $log)"
  start=$(date +%s)
  timeout --kill-after=60 "$limit" bash -c "$command" >"$log" 2>&1
  status=$?
  minutes=$(awk -v s="$(($(date +%s) - start))" 'BEGIN { printf "%.1f", s / 60 }')
  case $status in
    0) result=pass ;;
    124 | 137) result=TIMEOUT ;;
    *) result="FAIL($status)" ;;
  esac
  ((status == 0)) || failed=1
  printf '%-11s %-8s %9s  %s\n' "$j" "$result" "$minutes" "$log" | tee -a "$summary"
  if ((status != 0)); then
    tail -5 "$log" | sed 's/^/    /' | tee -a "$summary"
  fi
done
echo
cat "$summary"
exit "$failed"
