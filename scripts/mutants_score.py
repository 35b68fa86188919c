#!/usr/bin/env python3
"""The mutation score of a cargo-mutants run, and its survivors sorted by what docs/mutants.md says.

Usage: scripts/mutants_score.py OUTPUT_DIR EXPLAINED_MD [SECONDS]

OUTPUT_DIR is cargo-mutants' mutants.out; EXPLAINED_MD lists explained survivors as table rows
whose first cell is the mutant's name without its line and column (`src/f.rs: replace a with b
in g`) and whose second cell is its category (`equivalent` or `unobservable`). Prints the score
(killed / viable, killed counting time-outs), per file, the survivors by category, and every
survivor nobody has explained. Exits 1 when there is one.
"""
import collections
import json
import re
import sys


def key(name):
    """A mutant's name without line and column, so that moving code keeps its explanation."""
    return re.sub(r"^([^:]+):\d+:\d+:", r"\1:", name)


def explained(path):
    """Name → category, from the table rows of the markdown file."""
    known = {}
    for line in open(path, encoding="utf-8"):
        m = re.match(r"\|\s*`([^`]+)`\s*\|\s*(\w+)\s*\|", line)
        if m:
            # A `|` in a mutant's name is written `\|` so that the table keeps its columns.
            known[m.group(1).replace("\\|", "|")] = m.group(2)
    return known


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, md = sys.argv[1], sys.argv[2]
    seconds = float(sys.argv[3]) if len(sys.argv) > 3 else None
    try:
        outcomes = json.load(open(f"{out}/outcomes.json", encoding="utf-8"))
    except (OSError, ValueError) as e:
        sys.exit(f"mutants: cannot read {out}/outcomes.json: {e}")
    known = explained(md)
    rows = [o for o in outcomes["outcomes"] if o["scenario"] != "Baseline"]
    total = outcomes.get("total_mutants", len(rows))
    by = collections.Counter(o["summary"] for o in rows)
    caught, missed, timeout = by["CaughtMutant"], by["MissedMutant"], by["Timeout"]
    viable = caught + missed + timeout
    killed = caught + timeout
    print(f"mutants: {total} generated, {len(rows)} tried, {by['Unviable']} unviable (do not build)")
    if viable:
        print(f"score: {killed} killed / {viable} viable = {100 * killed / viable:.1f}% "
              f"({caught} by a failing test, {timeout} by a time-out; {missed} survived)")
    if len(rows) < total:
        print(f"untested: {total - len(rows)} (the time budget ran out)")
    if seconds is not None:
        print(f"time: {seconds / 60:.1f} min")
    files = collections.defaultdict(collections.Counter)
    for o in rows:
        files[o["scenario"]["Mutant"]["file"]][o["summary"]] += 1
    print("\nper file (killed / viable):")
    for f, c in sorted(files.items()):
        v = c["CaughtMutant"] + c["MissedMutant"] + c["Timeout"]
        print(f"  {f:24} {c['CaughtMutant'] + c['Timeout']:4} / {v:<4} survived {c['MissedMutant']}")
    survivors = [o["scenario"]["Mutant"]["name"] for o in rows if o["summary"] == "MissedMutant"]
    categories = collections.defaultdict(list)
    for name in survivors:
        categories[known.get(key(name), "UNEXPLAINED")].append(name)
    print("\nsurvivors by category:")
    for category, names in sorted(categories.items()):
        print(f"  {category}: {len(names)}")
    unexplained = categories.get("UNEXPLAINED", [])
    if unexplained:
        print(f"\n{len(unexplained)} survivors not explained in {md} (blind spots until shown otherwise):")
        for name in unexplained:
            print(f"  {name}")
        sys.exit(1)
    print(f"\nevery survivor is explained in {md}")


if __name__ == "__main__":
    main()
