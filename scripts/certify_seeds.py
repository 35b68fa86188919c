#!/usr/bin/env python3
"""Certifies every built-in at many seeds: refrast's own must pass, every mutant and course lab
must be caught, third-party drivers are reported.

Usage: scripts/certify_seeds.py [--seeds N] [--scale K] [--impl NAME ...] [--refrast PATH]

Runs `refrast certify --seed S --scale K` for seeds 1..N (and the default seed) per built-in.
Refrast's own implementations (`ours` in `refrast impls`) must pass every rule at every seed,
except where a rule states a known limit for that implementation in its sentence (a `may-fail`
line of expectations/ours.txt, printed as such). A mutant or a course lab must fail at least one rule at every seed: a
seed at which one passes is a seed the suite is blind at, and a crash or a timeout is no catch
(it is reported as a problem: the mutant, not the suite, broke). The reference restricted to one setting
(`reference, restricted`: 36 of them) must pass like refrast's own, but only when named with
--impl (the nightly workflow certifies them all at the default seed instead, with
`refrast certify --impl 'restricted:*'`). Exit 0 when all of that holds, 1 when not, 2 when
refrast cannot be run.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

# Failures the rules' sentences state as known limits of refrast's own implementations (both
# are clip-then-snap), as `may-fail` lines: expectations/ours.txt.
OURS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "expectations", "ours.txt")


def known_limits(path=OURS):
    """(implementation, rule) of every may-fail line of the expectation file."""
    limits, section = set(), None
    for line in open(path, encoding="utf-8"):
        body = line.split("#", 1)[0].strip()
        if body.startswith("["):
            section = body.strip("[]").strip()
        elif body and section and not body.startswith("taken "):
            rule, status = body.split()
            if status == "may-fail":
                limits.add((section, rule))
    return limits


def builtins(refrast):
    """Name → origin, from `refrast impls --json` (unavailable ones left out)."""
    out = subprocess.run([refrast, "impls", "--json"], capture_output=True, text=True, check=True).stdout
    return {i["name"]: i["origin"] for i in json.loads(out) if i["available"]}


def certify(refrast, name, seed, scale, folder):
    """The JSON entry of one certification and its wall time."""
    path = os.path.join(folder, f"{name.replace(':', '_')}-{seed}.json")
    args = [refrast, "certify", "--impl", name, "--seed", str(seed), "--scale", str(scale),
            "--json", path, "--report", os.path.join(folder, "pictures")]
    start = time.monotonic()
    run = subprocess.run(args, capture_output=True, text=True)
    if run.returncode not in (0, 1):
        sys.exit(f"certify_seeds: `{' '.join(args)}` exited {run.returncode}:\n{run.stderr}")
    return json.load(open(path))["implementations"][0], time.monotonic() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--scale", type=int, default=1)
    parser.add_argument("--impl", action="append", dest="impls")
    parser.add_argument("--refrast", default="target/release/refrast")
    args = parser.parse_args()
    if not os.access(args.refrast, os.X_OK):
        sys.exit(f"certify_seeds: no {args.refrast}; build it with `cargo build --release -p refrast-cli`")
    kinds = builtins(args.refrast)
    KNOWN_LIMITS = known_limits()
    names = args.impls or sorted(n for n, k in kinds.items() if k != "reference, restricted")
    seeds = [0x5EED_2026_0001] + list(range(1, args.seeds + 1))
    problems, limits = [], []
    folder = tempfile.mkdtemp(prefix="certify-seeds-")
    for name in names:
        kind = kinds.get(name, "unknown")
        for seed in seeds:
            entry, secs = certify(args.refrast, name, seed, args.scale, folder)
            if "skipped" in entry:
                print(f"{name:28} seed {seed:<16} SKIPPED: {entry['skipped']}")
                break
            failed = [r["id"] for r in entry["rules"] if r["status"] in ("fail", "flake")]
            broke = [f"{r['id']} ({r['status']})" for r in entry["rules"]
                     if r["status"] in ("crash", "timeout")]
            known = [r for r in failed if (name, r) in KNOWN_LIMITS]
            print(f"{name:28} seed {seed:<16} {len(failed):2} failed ({secs:6.1f} s)"
                  + (f"  {', '.join(failed)}" if failed else "")
                  + (f"  CRASHED: {', '.join(broke)}" if broke else ""))
            problems += [f"{name} {b} at seed {seed}: a crash is neither a pass nor a catch" for b in broke]
            if kind in ("ours", "reference, restricted"):
                limits += [(name, seed, r) for r in known]
                problems += [f"{name} fails {r} at seed {seed}" for r in failed if r not in known]
            elif kind in ("broken on purpose", "course lab") and not failed:
                problems.append(f"{name} ({kind}) passes every rule at seed {seed}: the suite is blind there")
    print(f"\nscale {args.scale}, {len(seeds)} seeds; reports in {folder}")
    for name, seed, rule in limits:
        print(f"known limit (stated in the rule): {name} fails {rule} at seed {seed}")
    for p in problems:
        print(f"PROBLEM: {p}")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
