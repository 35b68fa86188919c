#!/usr/bin/env python3
"""Runs the side-by-side benchmark (adapters/wgpu/benches/side_by_side.rs) and prints medians and
ratios to the reference: the reference, euc and lavapipe (drawing and reading back apart) on the
reference benchmark's two workloads, all in one process.

Usage: XDG_RUNTIME_DIR=/tmp/xdg python3 scripts/side_by_side.py [extra criterion args]
lavapipe needs Mesa (apt-get install mesa-vulkan-drivers libvulkan1); without it its rows are
missing and the benchmark says why.
"""
import json
import pathlib
import subprocess
import sys

root = pathlib.Path(__file__).resolve().parent.parent
cmd = ["cargo", "bench", "-p", "refrast-wgpu", "--bench", "side_by_side", "--", *sys.argv[1:]]
print("$", " ".join(cmd), file=sys.stderr)
subprocess.run(cmd, cwd=root, check=True)
meta = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"], cwd=root,
                      check=True, capture_output=True, text=True)
target = pathlib.Path(json.loads(meta.stdout)["target_directory"])
workloads = {"side-by-side-small": "100 000 × 10 px", "side-by-side-large": "1 000 × 50 000 px"}
impls = ["reference", "euc", "lavapipe-draw", "lavapipe-read-back"]
print(f"{'workload':<20} {'impl':<20} {'median':>11} {'vs reference':>13}")
for group, label in workloads.items():
    medians = {}
    for impl in impls:
        est = target / "criterion" / group / impl / "new/estimates.json"
        if est.exists():
            medians[impl] = json.loads(est.read_text())["median"]["point_estimate"] / 1e9
    base = medians.get("reference")
    for impl, s in medians.items():
        ratio = f"{s / base:>12.2f}x" if base else ""
        print(f"{label:<20} {impl:<20} {s * 1e3:>9.1f}ms {ratio}")
