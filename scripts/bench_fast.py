#!/usr/bin/env python3
"""Runs fast's benchmark and prints medians, Mtri/s, Mpix/s and ratios, side by side.

Usage: python3 scripts/bench_fast.py [--quick] [--threads 1,2,4] [--json FILE] [--no-swiftshader]
                                     [criterion args]

Every implementation of a table runs in the same process, so the ratios hold on a noisy
machine: `baseline` (the plain scalar loop), `reference`, and `fast_Nt` (fast on N threads, at
each count of --threads; the `vs 1t` column is the gain over one thread). Where Mesa's lavapipe
opens, `lavapipe` is its drawing time for a depth test and a primitive-id target, on as many
threads as the machine has cores, and `fast_resolve_Nt` is fast doing that same job on N
threads; `lavapipe_Nt` is lavapipe on N threads (`LP_NUM_THREADS`, which Mesa reads once a
process, so one more process of the bench per count). SwiftShader doing lavapipe's job runs in
a second process of the same bench (its Vulkan ICD is chosen by `VK_ICD_FILENAMES` before the
loader starts), as `swiftshader`. The `vs lvp` column is lavapipe's median over the row's
(`lavapipe_Nt` for `fast_resolve_Nt` where it ran, else `lavapipe`): above 1, faster than
lavapipe (only the resolve rows and `swiftshader` do its job).

--quick          one second of warm-up and three of measurement per row (a few minutes in all)
--threads LIST   fast's and lavapipe's thread counts, comma-separated (default: 1, 2 and the
                 machine's cores)
--json FILE      writes {"meta": {...}, "scenes": {scene: {implementation: median seconds}}}
--no-swiftshader skips the SwiftShader process
Other arguments go to criterion (a filter such as 'fast/small' picks scenes).

lavapipe needs `XDG_RUNTIME_DIR` set (any private folder) and `apt-get install
mesa-vulkan-drivers libvulkan1 vulkan-tools`; SwiftShader is in Debian's `chromium` package.
"""
import json
import os
import pathlib
import platform
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
SWIFTSHADER_ICD = "/usr/lib/chromium/vk_swiftshader_icd.json"
FIXED = ("baseline", "reference", "lavapipe", "swiftshader")
QUICK = ["--warm-up-time", "1", "--measurement-time", "3"]


def usage(message):
    print(f"bench_fast.py: {message}\n{__doc__}", file=sys.stderr)
    sys.exit(2)


def thread_list(text):
    """The thread counts of --threads: positive integers, in order, without repeats."""
    try:
        counts = sorted({int(n) for n in text.split(",")})
    except ValueError:
        counts = []
    if not counts or counts[0] < 1:
        usage(f"--threads takes thread counts of at least 1, comma-separated, got '{text}'")
    return counts


def parse(argv):
    """The script's own options, and the arguments left for criterion."""
    quick, json_path, swiftshader, rest = False, None, True, []
    threads = sorted({1, 2, os.cpu_count() or 1})
    args = iter(argv)
    for a in args:
        if a == "--quick":
            quick = True
        elif a == "--json":
            json_path = next(args, None)
            if json_path is None:
                usage("--json needs a file name")
        elif a.startswith("--json="):
            json_path = a.split("=", 1)[1]
        elif a == "--threads":
            value = next(args, None)
            if value is None:
                usage("--threads needs a list such as 1,2,4")
            threads = thread_list(value)
        elif a.startswith("--threads="):
            threads = thread_list(a.split("=", 1)[1])
        elif a == "--no-swiftshader":
            swiftshader = False
        elif a in ("-h", "--help"):
            print(__doc__)
            sys.exit(0)
        else:
            rest.append(a)
    return quick, threads, json_path, swiftshader, rest


def impls(threads):
    """Every row name a run with these thread counts can have, in table order."""
    per = lambda stem: [f"{stem}_{n}t" for n in threads]
    return ["baseline", "reference", *per("fast"), *per("fast_resolve"), "lavapipe", *per("lavapipe"),
            "swiftshader"]


def run_bench(args, env=None):
    """Runs the bench with criterion arguments `args`; returns its stdout."""
    cmd = ["cargo", "bench", "-p", "refrast-fast", "--bench", "fast", "--", *args]
    print("$", " ".join(cmd), file=sys.stderr)
    done = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, env=env)
    if done.returncode != 0:
        sys.stderr.write(done.stderr[-4000:])
        sys.exit(f"bench_fast.py: the bench failed (exit {done.returncode})")
    for line in done.stderr.splitlines():
        if "SKIPPED" in line:
            print(line, file=sys.stderr)
    return done.stdout


def medians(target, scene, names):
    """Median seconds per implementation of `scene` among `names`, from criterion's estimates."""
    found = {}
    for impl in names:
        for est in (target / "criterion" / "fast_" / scene / impl / "new/estimates.json",
                    target / "criterion" / f"fast_{scene}" / impl / "new/estimates.json"):
            if est.exists():
                found[impl] = json.loads(est.read_text())["median"]["point_estimate"] / 1e9
                break
    return found


def git(*args):
    done = subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True)
    return done.stdout.strip() if done.returncode == 0 else "unknown"


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def main():
    quick, threads, json_path, swiftshader, rest = parse(sys.argv[1:])
    names = impls(threads)
    timing = QUICK if quick else []
    # Old rows would pass for this run's: criterion keeps the last estimates of every row.
    meta = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"], cwd=ROOT,
                          check=True, capture_output=True, text=True)
    target = pathlib.Path(json.loads(meta.stdout)["target_directory"])
    for group in (target / "criterion").glob("fast_*"):
        for old in group.rglob("new/estimates.json"):
            old.unlink()
    counts_env = dict(os.environ, REFRAST_BENCH_THREADS=",".join(map(str, threads)))
    out = run_bench([*timing, *rest], counts_env)
    # Only the driver's rows in the processes that follow: everything else ran in the first.
    pattern = "|".join(re.escape(r) for r in rest if not r.startswith("-")) or "fast/"
    # Where lavapipe opened (its rows ran), once more per thread count.
    if re.search(r"/lavapipe\b", out):
        for n in threads:
            env = dict(counts_env, LP_NUM_THREADS=str(n), REFRAST_BENCH_DRIVER="lavapipe")
            run_bench([*timing, f"({pattern}).*/lavapipe_{n}t$"], env)
    if swiftshader and pathlib.Path(SWIFTSHADER_ICD).is_file():
        env = dict(counts_env, VK_ICD_FILENAMES=SWIFTSHADER_ICD, REFRAST_BENCH_DRIVER="swiftshader")
        run_bench([*timing, f"({pattern}).*/swiftshader"], env)
    elif swiftshader:
        print(f"swiftshader: SKIPPED: {SWIFTSHADER_ICD} is absent (apt-get install chromium)", file=sys.stderr)

    counts = {m[1]: (int(m[2]), int(m[3]), int(m[4]))
              for m in re.finditer(r"fragments (\S+) reference (\d+) baseline (\d+) triangles (\d+)", out)}
    simd = re.search(r"^simd (\S+)", out, re.M)
    print(f"{'scene':<13} {'impl':<16} {'median':>10} {'Mtri/s':>8} {'Mpix/s':>8} "
          f"{'vs ref':>8} {'vs base':>8} {'vs lvp':>7} {'vs 1t':>6}")
    table = {}
    for name, (ref_frags, base_frags, tris) in counts.items():
        found = medians(target, name, names)
        table[name] = found
        for impl in names:
            if impl not in found:
                continue
            s = found[impl]
            frags = base_frags if impl == "baseline" else ref_frags
            ratio = lambda other: f"{found[other] / s:>7.2f}x" if other in found else f"{'—':>8}"
            n = re.fullmatch(r"fast(?:_resolve)?_(\d+)t", impl)
            lavapipe = f"lavapipe_{n[1]}t" if n and f"lavapipe_{n[1]}t" in found else "lavapipe"
            one = "fast_resolve_1t" if impl.startswith("fast_resolve") else "fast_1t"
            scale = f"{found[one] / s:>5.2f}x" if n and one in found and impl != one else ""
            print(f"{name:<13} {impl:<16} {s * 1e3:>8.1f}ms {tris / s / 1e6:>8.2f} {frags / s / 1e6:>8.1f} "
                  f"{ratio('reference')} {ratio('baseline')} {ratio(lavapipe):>7} {scale:>6}")
    if json_path:
        document = {
            "meta": {
                "commit": git("rev-parse", "HEAD"),
                "dirty": bool(git("status", "--porcelain", "--untracked-files=no")),
                "cpu": cpu_model(),
                "cores": os.cpu_count(),
                # fast prints the SIMD level it chose; today's fast has none.
                "simd": simd[1] if simd else "none",
                # fast's and lavapipe_Nt's thread counts; `lavapipe` and `swiftshader` use as
                # many threads as the machine has cores.
                "threads": threads,
                "samples": 10,
                "quick": quick,
                "criterion_args": [*timing, *rest],
            },
            "scenes": table,
        }
        pathlib.Path(json_path).write_text(json.dumps(document, indent=2) + "\n")
        print(f"wrote {json_path}", file=sys.stderr)


if __name__ == "__main__":
    main()
