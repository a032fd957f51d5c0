#!/usr/bin/env python3
"""Issue 47: the whole `hqview analyze --no-render` on a refined real quad
surface of about 1M quads (Dolphin_padded's boundary quads split 13 x 13,
1,092,416 quads as binary VTU: bench/make_quad_surface.py) against the
363,520-hex refined Dolphin, run alternately (hex, quads, hex, quads, ...)
so that the machine's load hits both alike; medians of wall time, the
ratio against the issue's target (at most 2.5x the hex run), and the
self-intersection stage's share of the quad run (timings.json).

With --base HQVIEW_BASE (scripts/bench: $HQVIEW_BENCH_BASE), an earlier
build is run in the same rounds (base hex, hex, base quads, quads; base and
this build swapped every other round), and its ratio and share are
reported beside this build's: a before/after with same-run baselines.

usage: e2e_quads.py HQVIEW MESH_HEX MESH_QUADS OUT_DIR RESULT.json [--runs 3] [--base HQVIEW_BASE]
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


def timed(cmd, out, quads):
    """One run: wall, CPU and, for a quad run, the self-intersection's share of the stages."""
    wall, peak, cpu = run_once(cmd, out)
    line = "e2e_quads: %.2f s wall, %.2f s CPU, %.3f GB peak RSS" % (wall, cpu, peak / 2**30)
    share = None
    if quads:
        self_intersection, total = stage_seconds(out, "self-intersection")
        share = self_intersection / total if total > 0 else 0.0
        line += ", self-intersection %.2f s of %.2f s of stages (%.0f %%)" % (self_intersection, total, 100 * share)
    print(line + ": " + shlex.join(cmd), file=sys.stderr)
    return wall, cpu, share


def ratios(label, hexes, quads):
    med = lambda runs, i: statistics.median(r[i] for r in runs)
    ratio, cpu_ratio, share = med(quads, 0) / med(hexes, 0), med(quads, 1) / med(hexes, 1), med(quads, 2)
    print("e2e_quads: %s: quads/hexes wall %.2fx (<= 2.5x: %s), CPU %.2fx, self-intersection %.0f %% of the stages; "
          "medians hex %.2f s / %.2f s CPU, quads %.2f s / %.2f s CPU"
          % (label, ratio, "ok" if ratio <= 2.5 else "MISS", cpu_ratio, 100 * share, med(hexes, 0), med(hexes, 1),
             med(quads, 0), med(quads, 1)), file=sys.stderr)
    return {"label": label, "time_ratio": ratio, "cpu_ratio": cpu_ratio, "self_intersection_share": share,
            "hex_runs": hexes, "quad_runs": quads}


def main():
    p = argparse.ArgumentParser()
    for name in ("hqview", "mesh_hex", "mesh_quads", "out", "result"):
        p.add_argument(name)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--base", help="an earlier hqview, run in the same rounds")
    a = p.parse_args()
    cmd_of = lambda binary, mesh: [binary, "analyze", mesh, "-o", a.out, "--no-render", "-j", "2", "-q"]
    runs = {"this": ([], []), "base": ([], [])}
    for r in range(a.runs):
        sides = [(a.hqview, runs["this"])]
        if a.base:
            sides.append((a.base, runs["base"]))
            if r % 2 == 0:
                sides.reverse()
        for mesh, which in ((a.mesh_hex, 0), (a.mesh_quads, 1)):
            for binary, lists in sides:
                lists[which].append(timed(cmd_of(binary, mesh), a.out, which == 1))
    compared = [ratios("this build", *runs["this"])]
    if a.base:
        compared.append(ratios("base " + a.base, *runs["base"]))
    cmd = lambda mesh: cmd_of(a.hqview, mesh)
    this = compared[0]
    hexes = [w for w, _, _ in this["hex_runs"]]
    quads = [w for w, _, _ in this["quad_runs"]]
    shares = [s for _, _, s in this["quad_runs"]]
    wall_h, wall_q = statistics.median(hexes), statistics.median(quads)
    ratio, cpu_ratio, share = this["time_ratio"], this["cpu_ratio"], this["self_intersection_share"]

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
        json.dump({"e2e_cases": cases, "before_after": compared, "load_average": os.getloadavg()}, f, indent=1)


if __name__ == "__main__":
    main()
