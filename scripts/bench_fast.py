#!/usr/bin/env python3
"""Runs fast's benchmark and prints medians, Mtri/s, Mpix/s and ratios to the reference and baseline.

Usage: python3 scripts/bench_fast.py [extra criterion args, e.g. a filter like 'fast/small']
Every implementation runs in the same process, so the ratios hold on a noisy machine;
`fast_1t` and `fast_2t` are fast on 1 and 2 threads, and the last column is 2t over 1t.
Where Mesa's lavapipe opens, `lavapipe` is its drawing time for a depth test and a primitive-id
target, and `fast_resolve_2t` is fast doing that same job on 2 threads; the last column of
those rows is lavapipe's time over the row's (above 1: faster than lavapipe). lavapipe needs
`XDG_RUNTIME_DIR` set (any private folder) and `apt-get install mesa-vulkan-drivers libvulkan1`.
"""
import json
import pathlib
import re
import subprocess
import sys

root = pathlib.Path(__file__).resolve().parent.parent
cmd = ["cargo", "bench", "-p", "refrast-fast", "--bench", "fast", "--", *sys.argv[1:]]
print("$", " ".join(cmd), file=sys.stderr)
out = subprocess.run(cmd, cwd=root, check=True, capture_output=True, text=True).stdout
meta = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"], cwd=root, check=True, capture_output=True, text=True)
target = pathlib.Path(json.loads(meta.stdout)["target_directory"])
counts = {}
for m in re.finditer(r"fragments (\S+) reference (\d+) baseline (\d+) triangles (\d+)", out):
    counts[m[1]] = (int(m[2]), int(m[3]), int(m[4]))
impls = ("reference", "baseline", "fast_1t", "fast_2t", "fast_resolve_2t", "lavapipe")
print(f"{'scene':<13} {'impl':<16} {'median':>10} {'Mtri/s':>8} {'Mpix/s':>8} {'vs ref':>8} {'vs base':>8} {'2t/1t':>6}")
for name, (ref_frags, base_frags, tris) in counts.items():
    medians = {}
    for impl in impls:
        est = target / "criterion" / "fast_" / name / impl / "new/estimates.json"
        if not est.exists():
            est = target / "criterion" / f"fast_{name}" / impl / "new/estimates.json"
        if est.exists():
            medians[impl] = json.loads(est.read_text())["median"]["point_estimate"] / 1e9
    for impl in impls:
        if impl not in medians:
            continue
        s = medians[impl]
        frags = base_frags if impl == "baseline" else ref_frags
        vs_ref = medians["reference"] / s if "reference" in medians else float("nan")
        vs_base = medians["baseline"] / s if "baseline" in medians else float("nan")
        scale = ""
        if impl == "fast_2t" and "fast_1t" in medians:
            scale = f"{medians['fast_1t'] / s:>5.2f}x"
        elif impl.startswith("fast_resolve") and "lavapipe" in medians:
            scale = f"{medians['lavapipe'] / s:>5.2f}x"
        print(f"{name:<13} {impl:<16} {s * 1e3:>8.1f}ms {tris / s / 1e6:>8.2f} {frags / s / 1e6:>8.1f} {vs_ref:>7.2f}x {vs_base:>7.2f}x {scale:>6}")
