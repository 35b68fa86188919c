#!/usr/bin/env python3
"""Runs the reference benchmark and prints medians, Mtri/s, Mpix/s and reference/baseline ratios.

Usage: python3 scripts/bench_ratio.py [extra cargo bench args]
Both implementations run in the same process, so the ratio holds on a noisy machine.
"""
import json
import pathlib
import re
import subprocess
import sys

root = pathlib.Path(__file__).resolve().parent.parent
cmd = ["cargo", "bench", "--bench", "reference", "--", *sys.argv[1:]]
print("$", " ".join(cmd), file=sys.stderr)
out = subprocess.run(cmd, cwd=root, check=True, capture_output=True, text=True).stdout
meta = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"], cwd=root, check=True, capture_output=True, text=True)
target = pathlib.Path(json.loads(meta.stdout)["target_directory"])
counts = {}
for m in re.finditer(r"fragments (\S+) reference (\d+) baseline (\d+) triangles (\d+)", out):
    counts[m[1]] = (int(m[2]), int(m[3]), int(m[4]))
print(f"{'workload':<12} {'impl':<10} {'median':>10} {'Mtri/s':>8} {'Mpix/s':>8} {'vs baseline':>12}")
for name, (ref_frags, base_frags, tris) in counts.items():
    medians = {}
    for impl in ("reference", "baseline"):
        est = target / "criterion" / name / impl / "new/estimates.json"
        medians[impl] = json.loads(est.read_text())["median"]["point_estimate"] / 1e9
    for impl, frags in (("reference", ref_frags), ("baseline", base_frags)):
        s = medians[impl]
        ratio = s / medians["baseline"]
        print(f"{name:<12} {impl:<10} {s * 1e3:>8.1f}ms {tris / s / 1e6:>8.2f} {frags / s / 1e6:>8.1f} {ratio:>11.2f}x")
