#!/usr/bin/env python3
"""analyze's progress lines: on a terminal, not when piped, never with --quiet.

Writes a 72x72x72 structured hex mesh (373,248 hexes: reading, overlap and
writing each last a few tenths of a second), then runs the built hqview:
  - with standard error on a pseudo-terminal: one line per finished stage
    ("hqview: STAGE: S s"), one for every stage of timings.json, in its
    order; the running stage redrawn in place ("\\r\\033[K") with a bar
    ("[###...] N%") on at least one of the long stages;
  - piped: no stage line, no carriage return, no escape: only the last line;
  - piped with --verbose: the stage lines, plain (no "\\r", no escape);
  - --quiet on the terminal: nothing at all;
  - with HQVIEW_NO_HUGEPAGES=1 (no re-execution on huge pages): the same
    report.json.

Usage: check_progress.py HQVIEW WORK_DIR
"""

import json
import os
import pty
import re
import shutil
import subprocess
import sys

N = 72
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def write_grid(path, n):
    with open(path, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n" % ((n + 1) ** 3))
        f.write("".join(f"{x} {y} {z} 0\n" for z in range(n + 1) for y in range(n + 1) for x in range(n + 1)))
        f.write("Hexahedra\n%d\n" % (n ** 3))
        m = n + 1
        rows = []
        for z in range(n):
            for y in range(n):
                for x in range(n):
                    v = 1 + x + m * (y + m * z)
                    rows.append(f"{v} {v + 1} {v + 1 + m} {v + m} {v + m * m} {v + 1 + m * m} "
                                f"{v + 1 + m + m * m} {v + m + m * m} 0\n")
        f.write("".join(rows))
        f.write("End\n")


def run_on_terminal(args):
    """Runs args with standard error on a pseudo-terminal; returns (exit code, what the terminal got)."""
    master, slave = pty.openpty()
    process = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=slave, stdin=subprocess.DEVNULL)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:  # EIO: the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    os.close(master)
    return process.wait(), b"".join(chunks).decode("utf-8", "replace")


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    hqview, work = sys.argv[1:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    mesh = os.path.join(work, "grid.mesh")
    write_grid(mesh, N)
    common = [hqview, "analyze", mesh, "--no-render", "-j", "2"]

    code, tty = run_on_terminal([*common, "-o", os.path.join(work, "tty")])
    check(code == 0, f"terminal run exited {code}: {tty[-500:]!r}")
    with open(os.path.join(work, "tty", "timings.json")) as f:
        stages = [s["name"] for s in json.load(f)["stages"]]
    # What stays on the screen: each redraw starts with \r\033[K.
    finished = re.findall(r"hqview: ([^\r\n:]+): [0-9.e+-]+ s\r?\n", tty)
    check(finished == stages, f"finished lines {finished} are not the stages of timings.json {stages}")
    bars = re.findall(r"\r\x1b\[Khqview: ([^\r\n\[]+) \[#*\s*\] (\d+)% ", tty)
    long_stages = {"read", "metrics", "overlap", "write annotated.vtu"}
    check(any(name in long_stages for name, _ in bars), f"no progress bar on {sorted(long_stages)}: {bars[:5]}")
    check(all(0 <= int(p) <= 100 for _, p in bars), "a bar outside 0-100 %")
    check("report written to" in tty, "no closing line on the terminal")
    print(f"terminal: {len(finished)} stage lines, {len(bars)} bar redraws on "
          f"{sorted(set(n for n, _ in bars))}")

    piped = subprocess.run([*common, "-o", os.path.join(work, "piped")], capture_output=True, text=True)
    check(piped.returncode == 0, f"piped run exited {piped.returncode}")
    check("\r" not in piped.stderr and "\x1b" not in piped.stderr, f"piped: terminal control in {piped.stderr!r}")
    check(piped.stderr.strip().splitlines() == [f"hqview: report written to {os.path.join(work, 'piped', 'index.html')}"],
          f"piped: more than the last line: {piped.stderr!r}")

    verbose = subprocess.run([*common, "-o", os.path.join(work, "verbose"), "-v"], capture_output=True, text=True)
    lines = [l for l in verbose.stderr.splitlines() if re.match(r"hqview: [^:]+: [0-9.e+-]+ s \(peak memory", l)]
    check(len(lines) == len(stages), f"--verbose piped: {len(lines)} stage lines, timings.json has {len(stages)}")
    check("\r" not in verbose.stderr and "\x1b" not in verbose.stderr, "--verbose piped: terminal control")

    # The grid file is over 8 MiB, so hqview runs on huge pages (it executes
    # itself again with GLIBC_TUNABLES); without them, the same report.
    plain = subprocess.run([*common, "-o", os.path.join(work, "no_huge"), "-q"], capture_output=True, text=True,
                           env={**os.environ, "HQVIEW_NO_HUGEPAGES": "1"})
    check(plain.returncode == 0, f"HQVIEW_NO_HUGEPAGES=1 run exited {plain.returncode}")
    with open(os.path.join(work, "no_huge", "report.json"), "rb") as a, \
            open(os.path.join(work, "piped", "report.json"), "rb") as b:
        check(a.read() == b.read(), "report.json differs with and without huge pages")

    code, quiet = run_on_terminal([*common, "-o", os.path.join(work, "quiet"), "--quiet"])
    check(code == 0 and quiet == "", f"--quiet on a terminal printed {quiet[:200]!r}")

    print(f"{'FAILED' if failures else 'passed'}: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
