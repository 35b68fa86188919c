#!/usr/bin/env python3
"""Cases to first failure: how soon each public mutant is caught by its own rule family.

For every `mutant:` built-in, runs `refrast certify --impl MUTANT --rule FAMILY. --fail-fast`
at the default seed and cases, and reports the family's first failing rule (catalogue order),
the cases that rule ran before failing, and the cases all the family's rules ran in total
(the passing ones before it included). With --before, a JSON file an earlier run wrote with
--json, it prints both side by side.

Usage: scripts/cases_to_failure.py [--refrast PATH] [--json OUT] [--before OLD.json] [--mutant NAME]...
Exit: 0 when every mutant is caught by its family, 1 otherwise.
"""

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile


def mutants(refrast):
    """(name, family) of every mutant built-in, from `refrast impls --json`."""
    out = subprocess.run([refrast, "impls", "--json"], capture_output=True, text=True, check=True).stdout
    found = []
    for impl in json.loads(out):
        m = re.match(r"^the (\w+) rules must catch it", impl["description"])
        if impl["origin"] == "broken on purpose" and m:
            found.append((impl["name"], m.group(1)))
    return found


def first_failure(refrast, name, family):
    """The family's first failing rule, its cases, and the family's cases up to it."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "report.json")
        subprocess.run(
            [refrast, "certify", "--impl", name, "--rule", family + ".", "--fail-fast",
             "--json", path, "--report", os.path.join(tmp, "pictures")],
            capture_output=True, text=True, cwd=tmp,
        )
        if not os.path.exists(path):
            return None
        with open(path) as f:
            rules = json.load(f)["implementations"][0]["rules"]
    total = 0
    for r in rules:
        total += r["cases"]
        # A crash or a timeout stops --fail-fast too, but it is no catch: it is reported as such.
        if r["status"] in ("fail", "flake", "crash", "timeout"):
            return {"rule": r["id"], "cases": r["cases"], "family_cases": total, "status": r["status"]}
    return {"rule": None, "cases": None, "family_cases": total}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--refrast", default="target/release/refrast", help="the refrast binary")
    ap.add_argument("--json", help="write the results here")
    ap.add_argument("--before", help="results of an earlier run (its --json), shown beside")
    ap.add_argument("--mutant", action="append", help="only these (repeatable, e.g. affine-clipped)")
    args = ap.parse_args()
    if not os.path.exists(args.refrast):
        sys.exit(f"cases_to_failure: no binary at {args.refrast}; build it with `cargo build --release -p refrast-cli`")
    # certify runs in a scratch folder: a relative path must still name the binary.
    args.refrast = os.path.abspath(args.refrast)
    before = {}
    if args.before:
        with open(args.before) as f:
            before = json.load(f)
    results = {}
    ok = True
    chosen = mutants(args.refrast)
    if args.mutant:
        wanted = {m if m.startswith("mutant:") else "mutant:" + m for m in args.mutant}
        chosen = [c for c in chosen if c[0] in wanted]
    print("| mutant | family | first failing rule | cases | family cases to it |" + (" before |" if before else ""))
    print("|---|---|---|---|---|" + ("---|" if before else ""))
    for name, family in chosen:
        r = first_failure(args.refrast, name, family)
        results[name] = r
        crashed = r is not None and r.get("status") in ("crash", "timeout")
        if r is None or r["rule"] is None or crashed:
            ok = False
        rule = f"`{r['rule']}`" if r and r["rule"] else "**not caught**"
        if crashed:
            rule += f" (**{r['status']}**: not a catch)"
        cases = r["cases"] if r and r["rule"] else "–"
        total = r["family_cases"] if r else "–"
        row = f"| `{name}` | {family} | {rule} | {cases} | {total} |"
        if before:
            b = before.get(name)
            if b is None:
                row += " (new) |"
            elif b["rule"] is None:
                row += f" not caught ({b['family_cases']} cases) |"
            else:
                row += f" `{b['rule']}` {b['cases']} ({b['family_cases']}) |"
        print(row, flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
