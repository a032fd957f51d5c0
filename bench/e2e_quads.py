#!/usr/bin/env python3
"""Issue 47: the whole `hqview analyze --no-render` on a refined real quad
surface of about 1M quads (Dolphin_padded's boundary quads split 13 x 13,
1,092,416 quads as binary VTU: bench/make_quad_surface.py) against the
363,520-hex refined Dolphin, run alternately (hex, quads, hex, quads, ...)
so that the machine's load hits both alike; medians of wall time, the
ratio against the issue's target (at most 2.5x the hex run), and the
self-intersection stage's share of the quad run (timings.json).

usage: e2e_quads.py HQVIEW MESH_HEX MESH_QUADS OUT_DIR RESULT.json [--runs 3]
"""
import argparse
import json
import os
import shlex
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from e2e import run_once  # noqa: E402  (one timed run: wall, wait4's peak RSS and CPU)


def stage_seconds(out, name):
    """A stage's seconds and the sum of all stages in OUT/timings.json."""
    with open(os.path.join(out, "timings.json")) as f:
        stages = json.load(f)["stages"]
    total = sum(s["seconds"] for s in stages)
    return sum(s["seconds"] for s in stages if s["name"] == name), total


def main():
    p = argparse.ArgumentParser()
    for name in ("hqview", "mesh_hex", "mesh_quads", "out", "result"):
        p.add_argument(name)
    p.add_argument("--runs", type=int, default=3)
    a = p.parse_args()
    cmd = lambda mesh: [a.hqview, "analyze", mesh, "-o", a.out, "--no-render", "-j", "2", "-q"]
    hexes, quads, shares, cpus = [], [], [], {a.mesh_hex: [], a.mesh_quads: []}
    for _ in range(a.runs):
        for mesh, runs in ((a.mesh_hex, hexes), (a.mesh_quads, quads)):
            wall, peak, cpu = run_once(cmd(mesh), a.out)
            runs.append(wall)
            cpus[mesh].append(cpu)
            line = "e2e_quads: %.2f s wall, %.2f s CPU, %.3f GB peak RSS" % (wall, cpu, peak / 2**30)
            if runs is quads:
                self_intersection, total = stage_seconds(a.out, "self-intersection")
                shares.append(self_intersection / total if total > 0 else 0.0)
                line += ", self-intersection %.2f s of %.2f s of stages (%.0f %%)" % (
                    self_intersection, total, 100 * shares[-1])
            print(line + ": " + shlex.join(cmd(mesh)), file=sys.stderr)
    wall_h, wall_q = statistics.median(hexes), statistics.median(quads)
    ratio = wall_q / wall_h
    share = statistics.median(shares)
    cpu_ratio = statistics.median(cpus[a.mesh_quads]) / statistics.median(cpus[a.mesh_hex])

    def case(label, command, value, unit, target, ok, runs):
        return {"label": label, "command": command, "value": value, "unit": unit, "target": target, "ok": ok,
                "runs": runs}

    cases = [
        case("hqview 363,520 hexes --no-render (baseline, wall)", shlex.join(cmd(a.mesh_hex)), wall_h, "s",
             "baseline", True, hexes),
        case("hqview 1,092,416-quad surface (binary VTU) --no-render (wall)", shlex.join(cmd(a.mesh_quads)), wall_q,
             "s", "baseline", True, quads),
        case("quads / hexes, median wall time (issue 47)", "the two rows above", ratio, "x", "<= 2.5x",
             ratio <= 2.5, []),
        case("quads / hexes, median CPU time (user + system; steadier on a loaded machine)", "the two rows above",
             cpu_ratio, "x", "baseline", True, []),
        case("self-intersection's share of the quad run's stages (issue 47)", "timings.json", 100 * share, "%",
             "baseline", True, [100 * s for s in shares]),
    ]
    for c in cases:
        print("e2e_quads: %s: %.3f %s (%s%s)" % (c["label"], c["value"], c["unit"], c["target"],
                                                "" if c["target"] == "baseline" else (": ok" if c["ok"] else ": MISS")),
              file=sys.stderr)
    with open(a.result, "w") as f:
        json.dump({"e2e_cases": cases, "load_average": os.getloadavg()}, f, indent=1)


if __name__ == "__main__":
    main()
