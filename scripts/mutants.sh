#!/usr/bin/env bash
# Mutation testing of the reference (src/) with cargo-mutants: each mutant is judged by the
# reference's own tests and the whole conformance catalogue (tests/catalogue.rs), stopping at the
# first failing rule (REFRAST_FAIL_FAST). Then prints the score and every survivor not yet
# explained in docs/mutants.md.
#
# Usage: [REFRAST_MUTATE=reference|oracles|lab] scripts/mutants.sh [MINUTES] [cargo-mutants arguments...]
#   REFRAST_MUTATE=oracles mutates the suite's ground truth instead (conformance/src/oracle/:
#            brute force, ray cast, outlines), judged by the conformance crate's tests and the
#            reference's catalogue: a wrong oracle fails the correct reference. Output then
#            goes to oracles/mutants.out/.
#   REFRAST_MUTATE=lab mutates only the lab pipeline (camera, lines, the render pipeline, the
#            scenes), which the Rasterizer trait does not reach, judged by the tests that do
#            (the unit tests and tests/integration/, the lab's lines.rs, golden.rs and pipeline.rs
#            among them) and not the catalogue, so each
#            mutant takes seconds instead of a minute. Output goes to lab/mutants.out/.
#   MINUTES  wall-time budget (default 240); when it runs out the mutants not yet tried are
#            counted as untested, and the score covers those tried.
#   e.g.     scripts/mutants.sh 30 --file src/edge.rs
# Output: mutants.out/ (cargo-mutants' outcomes and logs), and the summary on stdout.
# Exit: 0 when every survivor is explained, 1 when one is not, 2 when cargo-mutants is missing
# and cannot be installed.
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-240}
shift || true

if ! cargo mutants --version >/dev/null 2>&1; then
  echo "== cargo install cargo-mutants (about 3 minutes)"
  cargo install cargo-mutants --locked --version '^27' >/dev/null 2>&1 || {
    echo "mutants: cargo-mutants could not be installed" >&2
    exit 2
  }
fi

echo "== cargo mutants (config in .cargo/mutants.toml), ${minutes} min budget"
case "${REFRAST_MUTATE:-reference}" in
  reference)
    scope=(--package refrast)
    out=.
    ;;
  oracles)
    scope=(--package refrast-conformance --test-package refrast --test-package refrast-conformance
      -f 'conformance/src/oracle/**/*.rs')
    out=oracles
    mkdir -p "$out"
    ;;
  lab)
    # .cargo/mutants.toml would add the catalogue too; name the reference's own tests instead
    # (the lab's among them: tests/integration/lines.rs, golden.rs and pipeline.rs).
    scope=(--no-config --package refrast --test-package refrast --profile mutants
      --cargo-test-arg=--lib --cargo-test-arg=--test=integration
      -f src/camera.rs -f src/dda.rs -f src/pipeline.rs -f src/scenes.rs)
    out=lab
    mkdir -p "$out"
    ;;
  *)
    echo "mutants: REFRAST_MUTATE is reference, oracles or lab, not '$REFRAST_MUTATE'" >&2
    exit 2
    ;;
esac
started=$(date +%s)
status=0
REFRAST_FAIL_FAST=1 timeout --signal=INT --kill-after=60 "$((minutes * 60))" \
  cargo mutants "${scope[@]}" --output "$out" --no-shuffle "$@" || status=$?
elapsed=$(($(date +%s) - started))
# cargo-mutants: 0 all caught, 2 some missed, 3 some timed out, 4 baseline failed; timeout: 124/130.
case $status in
  0 | 2 | 3 | 124 | 130) ;;
  *)
    echo "mutants: cargo mutants failed (exit $status); see $out/mutants.out/debug.log" >&2
    exit "$status"
    ;;
esac
python3 scripts/mutants_score.py "$out/mutants.out" docs/mutants.md "$elapsed"
