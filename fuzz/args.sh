# Shared by fuzz/nightly.sh and fuzz/rate.sh (sourced, not run): the fuzz targets, and the
# parsing of `SCRIPT [SECONDS] [TARGET...]` into $seconds and the array targets.
#   parse_fuzz_args SCRIPT DEFAULT_SECONDS "$@"    exits 2, saying why, on a bad argument
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
