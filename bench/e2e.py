#!/usr/bin/env python3
"""The end-to-end stage of scripts/bench: runs `hqview analyze MESH -o OUT
--no-render -j THREADS -q` RUNS times (OUT emptied before each run, outside
the timing) and writes each run's wall time and peak RSS (the child's
maximum resident set size from wait4) as JSON for report.py.

usage: e2e.py HQVIEW MESH OUT_DIR RESULT.json --hexes N [--threads 2] [--runs 3]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("hqview")
    ap.add_argument("mesh")
    ap.add_argument("out")
    ap.add_argument("result")
    ap.add_argument("--hexes", type=int, required=True)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--target-wall-s", type=float, default=60.0)
    ap.add_argument("--target-rss-gb", type=float, default=6.0)
    a = ap.parse_args()
    runs = []
    for i in range(a.runs):
        shutil.rmtree(a.out, ignore_errors=True)
        cmd = [a.hqview, "analyze", a.mesh, "-o", a.out, "--no-render", "-j", str(a.threads), "-q"]
        start = time.monotonic()
        child = subprocess.Popen(cmd)
        _, status, usage = os.wait4(child.pid, 0)
        wall = time.monotonic() - start
        code = os.waitstatus_to_exitcode(status)
        if code != 0:
            sys.exit("e2e: %s exited with %d" % (" ".join(cmd), code))
        runs.append({"wall_s": wall, "max_rss_kb": usage.ru_maxrss, "user_s": usage.ru_utime,
                     "sys_s": usage.ru_stime})
        print("e2e run %d/%d: %.1f s wall, %.2f GB peak RSS, %.1f s user + %.1f s sys" %
              (i + 1, a.runs, wall, usage.ru_maxrss / 1024 / 1024, usage.ru_utime, usage.ru_stime), file=sys.stderr)
    shutil.rmtree(a.out, ignore_errors=True)
    with open(a.result, "w") as f:
        json.dump({"e2e": {"hexes": a.hexes, "threads": a.threads, "target_wall_s": a.target_wall_s,
                           "target_rss_gb": a.target_rss_gb, "runs": runs,
                           "load_average": os.getloadavg()}}, f, indent=1)


if __name__ == "__main__":
    main()
