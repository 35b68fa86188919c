#!/usr/bin/env python3
"""Drives `refrast view` on a virtual X server and checks what a person would see.

Starts Xvfb on a free display, opens the viewer, sends keys and mouse drags with xdotool, and
reads the window's pixels back (python3-xlib). Checks, each a failure when it does not hold:

1. the room in fill mode is not blank (many colours, no colour covering nearly everything);
2. the picture changes when the camera moves (W and the left arrow held), and when the mouse
   drags with the left button held;
3. P writes a PNG; resizing the window resizes the picture; closing the window exits with 0;
4. the aligned plane in overdraw mode changes when I reaches a mutant (its cracked or doubled
   shared edges), compared with the fast rasterizer's picture;
5. --frames 30 closes by itself and prints its render and whole-frame times.

The status lines (the top BAND rows) name the implementation, so pictures are compared below it.

    python3 scripts/check_viewer.py [--refrast target/release/refrast] [--out DIR]

--out keeps the screenshots (PNG) there. Without Xvfb, xdotool or python3-xlib it says so and
exits 0, unless REFRAST_REQUIRE_VIEWER=1 (then 1). Takes about 10 s.
"""

import argparse
import os
import queue
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# Rows of the status lines at the top of the window (cli/src/view/overlay.rs, BAND).
BAND = 22
TIMEOUT = 20.0


def fail(message):
    sys.exit(f"viewer check: FAILED: {message}")


def missing_tools():
    """What of Xvfb, xdotool and python3-xlib is missing, as apt package names."""
    missing = [pkg for exe, pkg in (("Xvfb", "xvfb"), ("xdotool", "xdotool")) if not shutil.which(exe)]
    try:
        import Xlib.display  # noqa: F401
    except ImportError:
        # Debian's python3-xlib is installed for Debian's Python; a Python of one's own (pyenv,
        # a virtual environment) first on PATH lacks it: run this script under Debian's instead.
        system = "/usr/bin/python3"
        if os.path.realpath(sys.executable) != os.path.realpath(system) and subprocess.run(
                [system, "-c", "import Xlib.display"], capture_output=True, check=False).returncode == 0:
            os.execv(system, [system, *sys.argv])
        missing.append("python3-xlib")
    return missing


class Xvfb:
    """A virtual X server on a display it picks itself (-displayfd), stopped on exit."""

    def __init__(self):
        read, write = os.pipe()
        self.process = subprocess.Popen(
            ["Xvfb", "-displayfd", str(write), "-screen", "0", "1024x768x24", "-nolisten", "tcp"],
            pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(write)
        with os.fdopen(read) as f:
            number = f.readline().strip()
        if not number:
            fail(f"Xvfb did not start (exit {self.process.poll()})")
        self.display = f":{number}"

    def stop(self):
        self.process.terminate()
        try:
            self.process.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.process.kill()


class Viewer:
    """`refrast view ARGS` on `display`, its stdout read line by line."""

    def __init__(self, refrast, display, args, cwd):
        self.env = dict(os.environ, DISPLAY=display)
        self.process = subprocess.Popen([refrast, "view", *args], env=self.env, cwd=cwd,
                                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.lines = queue.Queue()
        self.log = []
        threading.Thread(target=self._read, daemon=True).start()
        self.title = f"refrast view: {args[0]}"
        found = self.xdotool("search", "--sync", "--name", f"^{re.escape(self.title)}$", timeout=TIMEOUT)
        self.window = int(found.split()[0])
        import Xlib.display
        self.x = Xlib.display.Display(display)
        self.xwindow = self.x.create_resource_object("window", self.window)
        # Keys go to the focused window; the pointer rests on it for the drags.
        self.xdotool("windowfocus", "--sync", str(self.window))
        self.xdotool("mousemove", "--window", str(self.window), "100", "100")
        self.settle()

    def _read(self):
        for line in self.process.stdout:
            self.log.append(line.rstrip("\n"))
            self.lines.put(line.rstrip("\n"))
        self.lines.put(None)

    def xdotool(self, *args, timeout=10.0):
        done = subprocess.run(["xdotool", *args], env=self.env, capture_output=True, text=True,
                              timeout=timeout, check=False)
        if done.returncode != 0:
            fail(f"xdotool {' '.join(args)}: exit {done.returncode}: {done.stderr.strip()}; "
                 f"viewer said: {self.log[-5:]}")
        return done.stdout

    def expect(self, pattern):
        """Waits for a line of the viewer's stdout matching `pattern`; returns the match."""
        deadline = time.monotonic() + TIMEOUT
        while time.monotonic() < deadline:
            try:
                line = self.lines.get(timeout=0.2)
            except queue.Empty:
                continue
            if line is None:
                fail(f"the viewer exited ({self.process.wait()}) waiting for /{pattern}/: {self.log[-5:]}")
            match = re.search(pattern, line)
            if match:
                return match
        fail(f"no line /{pattern}/ from the viewer in {TIMEOUT:.0f} s: {self.log[-5:]}")

    def settle(self):
        """Lets a few frames (60 a second, slower for the reference) reach the screen."""
        time.sleep(0.4)

    def press(self, key, answer):
        self.xdotool("key", key)
        match = self.expect(answer)
        self.settle()
        return match

    def hold(self, key, seconds):
        self.xdotool("keydown", key)
        time.sleep(seconds)
        self.xdotool("keyup", key)
        self.settle()

    def shot(self):
        """The window's pixels as (width, height, rows of RGB bytes)."""
        from Xlib import X
        g = self.xwindow.get_geometry()
        image = self.xwindow.get_image(0, 0, g.width, g.height, X.ZPixmap, 0xFFFFFFFF)
        data = image.data
        stride = len(data) // g.height
        rows = []
        for y in range(g.height):
            row = data[y * stride:y * stride + 4 * g.width]
            # 24-bit TrueColor in 32-bit words, least significant byte first: B, G, R, pad.
            rgb = bytearray(3 * g.width)
            rgb[0::3], rgb[1::3], rgb[2::3] = row[2::4], row[1::4], row[0::4]
            rows.append(bytes(rgb))
        return g.width, g.height, rows

    def close(self):
        """Asks the window to close as a window manager's close button does (WM_DELETE_WINDOW)."""
        from Xlib import X, protocol
        protocols = self.x.intern_atom("WM_PROTOCOLS")
        delete = self.x.intern_atom("WM_DELETE_WINDOW")
        event = protocol.event.ClientMessage(window=self.xwindow, client_type=protocols,
                                             data=(32, [delete, X.CurrentTime, 0, 0, 0]))
        self.xwindow.send_event(event, event_mask=X.NoEventMask)
        self.x.flush()
        return self.wait()

    def wait(self):
        try:
            return self.process.wait(timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            fail(f"the viewer did not exit in {TIMEOUT:.0f} s: {self.log[-5:]}")

    def stop(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


def below_band(shot):
    return shot[2][BAND:]


def differing(a, b):
    """Pixels that differ between two shots of the same size, below the status line."""
    if a[:2] != b[:2]:
        return max(a[0] * a[1], b[0] * b[1])
    count = 0
    for ra, rb in zip(below_band(a), below_band(b)):
        if ra != rb:
            count += sum(ra[i:i + 3] != rb[i:i + 3] for i in range(0, len(ra), 3))
    return count


def check_not_blank(shot, what):
    pixels = {}
    for row in below_band(shot):
        for i in range(0, len(row), 3):
            pixels[row[i:i + 3]] = pixels.get(row[i:i + 3], 0) + 1
    total = sum(pixels.values())
    top = max(pixels.values())
    print(f"viewer check: {what}: {len(pixels)} colours, the commonest on {100 * top / total:.0f}%")
    if len(pixels) < 16 or top > 0.9 * total:
        fail(f"{what} looks blank: {len(pixels)} colours, one on {top} of {total} pixels")


def check_changed(before, after, what, least):
    n = differing(before, after)
    print(f"viewer check: {what}: {n} pixels changed")
    if n < least:
        fail(f"{what}: only {n} pixels changed (want {least} or more)")


def save_png(shot, path):
    """Writes a shot as an 8-bit RGB PNG (no imaging library needed)."""
    width, height, rows = shot

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    raw = b"".join(b"\x00" + row for row in rows)
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    Path(path).write_bytes(png)


def room(refrast, display, out):
    """Checks 1 to 3 on the room."""
    viewer = Viewer(refrast, display, ["room", "--size", "640x480", "--output", str(out)], out)
    try:
        start = viewer.shot()
        save_png(start, out / "room.png")
        check_not_blank(start, "room, fill")
        viewer.hold("w", 0.3)
        viewer.hold("Left", 0.3)
        moved = viewer.shot()
        check_changed(start, moved, "W and the left arrow held", 5000)
        # Slowly enough that frames see the button held between moves, however slow the build.
        viewer.xdotool("mousedown", "1")
        viewer.settle()
        for _ in range(4):
            viewer.xdotool("mousemove_relative", "--", "20", "-6")
            viewer.settle()
        viewer.xdotool("mouseup", "1")
        viewer.settle()
        check_changed(moved, viewer.shot(), "a mouse drag", 5000)
        saved = Path(viewer.press("p", r"^saved (.*\.png)$").group(1))
        if not saved.is_file() or not saved.read_bytes().startswith(b"\x89PNG"):
            fail(f"P said it saved {saved}, but there is no PNG there")
        print(f"viewer check: P saved {saved.name}")
        viewer.xdotool("windowsize", str(viewer.window), "320", "200")
        viewer.expect(r"^size 320x200$")
        viewer.settle()
        small = viewer.shot()
        if small[:2] != (320, 200):
            fail(f"the window is {small[0]}x{small[1]} after resizing to 320x200")
        check_not_blank(small, "room, resized to 320x200")
        status = viewer.close()
        if status != 0:
            fail(f"closing the window: exit {status}, want 0")
        print("viewer check: closing the window exits with 0")
    finally:
        viewer.stop()


def overdraw(refrast, display, out):
    """Check 4 on the aligned plane: the fast rasterizer, then the first mutant of I's cycle."""
    viewer = Viewer(refrast, display, ["aligned-plane", "--mode", "overdraw", "--impl", "fast"], out)
    try:
        fast = viewer.shot()
        save_png(fast, out / "overdraw-fast.png")
        name = "fast"
        for _ in range(10):
            name = viewer.press("i", r"^impl (\S+)$").group(1)
            if name.startswith("mutant:"):
                break
        else:
            fail("I never reached a mutant in ten presses")
        mutant = viewer.shot()
        save_png(mutant, out / "overdraw-mutant.png")
        check_changed(fast, mutant, f"overdraw, fast -> {name}", 1000)
        viewer.xdotool("key", "Escape")
        status = viewer.wait()
        if status != 0:
            fail(f"Escape: exit {status}, want 0")
    finally:
        viewer.stop()


def measure(refrast, display):
    """`--frames` draws that many frames, closes by itself and prints the times."""
    done = subprocess.run([refrast, "view", "room", "--size", "320x240", "--frames", "30"],
                          env=dict(os.environ, DISPLAY=display), capture_output=True, text=True,
                          timeout=120, check=False)
    line = done.stdout.strip().splitlines()[-1] if done.stdout.strip() else ""
    pattern = (r"^room 320x240, fast \(1 thread\), fill: 20 frames \(after 10 not counted\): render median "
               r"[0-9.]+ ms \(mean [0-9.]+\), whole frame median [0-9.]+ ms \(mean [0-9.]+\) = [0-9]+ fps$")
    if done.returncode != 0 or not re.match(pattern, line):
        fail(f"--frames 30: exit {done.returncode}, last line {line!r}, stderr {done.stderr.strip()!r}")
    print(f"viewer check: --frames 30 says: {line}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--refrast", default=str(ROOT / "target" / "release" / "refrast"))
    parser.add_argument("--out", help="where to keep the screenshots [a temporary folder]")
    args = parser.parse_args()
    missing = missing_tools()
    if missing:
        if os.environ.get("REFRAST_REQUIRE_VIEWER") == "1":
            fail(f"{', '.join(missing)} missing, and REFRAST_REQUIRE_VIEWER=1 requires them")
        print(f"viewer check: SKIPPED: {', '.join(missing)} not installed (apt-get install {' '.join(missing)})")
        return
    refrast = str(Path(args.refrast).resolve())
    if not os.access(refrast, os.X_OK):
        fail(f"no refrast binary at {refrast}; build it (cargo build --release) or pass --refrast")
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="refrast-viewer-") as scratch:
        out = Path(args.out).resolve() if args.out else Path(scratch)
        out.mkdir(parents=True, exist_ok=True)
        server = Xvfb()
        try:
            room(refrast, server.display, out)
            overdraw(refrast, server.display, out)
            measure(refrast, server.display)
        finally:
            server.stop()
    print(f"viewer check: passed in {time.monotonic() - started:.1f} s")


if __name__ == "__main__":
    main()
