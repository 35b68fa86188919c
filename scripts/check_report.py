#!/usr/bin/env python3
"""Loads certify's index.html in headless Chromium and checks what a person would see.

Certifies the reference beside two mutants that fail (small --cases, so it takes seconds), then
renders DIR/index.html with `chromium --headless`: the DOM after load must hold the matrix and a
rules table per implementation, and every embedded picture must have decoded in the browser
(the page's own script writes the count into `data-images-decoded` on <body>); a screenshot
must come out as a non-empty PNG.

    python3 scripts/check_report.py [--refrast target/release/refrast] [--out DIR]

Without Chromium it says so and exits 0, unless REFRAST_REQUIRE_BROWSER=1 (then 1). Chromium's
own warnings (dbus, GPU) go to DIR/chromium.log.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
IMPLS = ["reference", "mutant:inclusive-edges", "mutant:depth-without-test"]
PNG = b"\x89PNG\r\n\x1a\n"


def browser():
    """The Chromium on PATH, or None."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def chromium(exe, out, *args):
    """Runs headless Chromium with `args`; its stdout, its stderr appended to out/chromium.log."""
    command = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
               f"--user-data-dir={out / 'chromium-profile'}", *args]
    with open(out / "chromium.log", "ab") as log:
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=log, timeout=120, check=False)
    if done.returncode != 0:
        sys.exit(f"browser check: chromium exited {done.returncode}; see {out / 'chromium.log'}")
    return done.stdout.decode("utf-8", "replace")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--refrast", default=str(ROOT / "target" / "release" / "refrast"))
    parser.add_argument("--out", help="where to write the report, DOM and screenshot [a temporary folder]")
    args = parser.parse_args()
    exe = browser()
    if exe is None:
        if os.environ.get("REFRAST_REQUIRE_BROWSER") == "1":
            sys.exit("browser check: no chromium, and REFRAST_REQUIRE_BROWSER=1 requires it")
        print("browser check: SKIPPED: no chromium on PATH (apt-get install chromium)")
        return
    out = Path(args.out or tempfile.mkdtemp(prefix="refrast-report-check-")).resolve()
    out.mkdir(parents=True, exist_ok=True)
    report = out / "report"
    certify = [args.refrast, "certify", "--rule", "*", "--cases", "20", "--report", str(report)]
    for name in IMPLS:
        certify += ["--impl", name]
    done = subprocess.run(certify, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, check=False)
    if done.returncode != 1:
        sys.stdout.write(done.stdout.decode("utf-8", "replace"))
        sys.exit(f"browser check: certify exited {done.returncode}, where the mutants' failures give 1")
    page = report / "index.html"
    url = page.as_uri()

    dom = chromium(exe, out, "--dump-dom", url)
    (out / "dom.html").write_text(dom)
    images = len(re.findall(r"<img\b", dom))
    decoded = re.search(r'<body[^>]*\bdata-images-decoded="(\d+)"', dom)
    tables = len(re.findall(r'<table class="rules">', dom))
    matrix = '<table class="matrix">' in dom
    rows = len(re.findall(r'<tr id="r\d+-\d+">', dom))
    failures = len(re.findall(r'<div class="failure"', dom))
    problems = []
    if decoded is None:
        problems.append("the page's script did not run (no data-images-decoded on <body>)")
    elif int(decoded.group(1)) != images:
        problems.append(f"{decoded.group(1)} of {images} pictures decoded")
    if images == 0:
        problems.append("no picture on the page")
    if tables != len(IMPLS):
        problems.append(f"{tables} rules tables for {len(IMPLS)} implementations")
    if not matrix:
        problems.append("no matrix")
    if failures == 0:
        problems.append("no failure detail")

    shot = out / "report.png"
    chromium(exe, out, f"--screenshot={shot}", "--window-size=1280,2000", "--hide-scrollbars", url)
    if not shot.is_file() or shot.stat().st_size == 0 or not shot.read_bytes().startswith(PNG):
        problems.append(f"no screenshot at {shot}")
    if problems:
        sys.exit("browser check: FAILED: " + "; ".join(problems) + f" (outputs in {out})")
    print(f"browser check: {tables} tables, {rows} rule rows, matrix, {failures} failures, "
          f"{images} of {images} pictures decoded, screenshot {shot.stat().st_size} bytes ({out})")


if __name__ == "__main__":
    main()
