# Shared by fuzz/nightly.sh and fuzz/rate.sh (sourced, not run): the fuzz targets, and the
# parsing of `SCRIPT [SECONDS] [TARGET...]` into $seconds and the array targets.
#   parse_fuzz_args SCRIPT DEFAULT_SECONDS "$@"    exits 2, saying why, on a bad argument
# libFuzzer's comparison tracing is off unless FUZZ_TRACE_COMPARES=1: it instruments every
# integer comparison of the oracles' sample loops, which halved `clipping`'s and `watertight`'s
# executions a second, and over 90 s from the same seeds both builds of `clipping` reached the
# same coverage (1 552 and 1 553 edges; docs/fuzzing.md).
instrument=(--no-trace-compares)
[[ ${FUZZ_TRACE_COMPARES:-0} == 1 ]] && instrument=()
all_targets=(robustness differential fast watertight clipping depth_order interpolation pipeline mesh_load)
parse_fuzz_args() {
  local script=$1
  seconds=${3:-$2}
  if ! [[ $seconds =~ ^[0-9]+$ ]] || ((seconds == 0)); then
    echo "usage: $script [SECONDS] [TARGET...]; SECONDS must be a positive integer, got '$seconds'" >&2
    exit 2
  fi
  shift $(($# > 2 ? 3 : 2))
  targets=("$@")
  ((${#targets[@]})) || targets=("${all_targets[@]}")
  local t
  for t in "${targets[@]}"; do
    if [[ " ${all_targets[*]} " != *" $t "* ]]; then
      echo "$script: unknown target '$t'; the targets are: ${all_targets[*]}" >&2
      exit 2
    fi
  done
}
