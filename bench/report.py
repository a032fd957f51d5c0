#!/usr/bin/env python3
"""Prints one table of the medians of Google Benchmark JSON results, each
benchmark's ratio to the baseline of its family measured in the same run,
and its issue target, plus the end-to-end stage of scripts/bench.

A benchmark named BM_<Family>_HQView[/args] is compared with
BM_<Family>_Baseline<Anything> (the baseline's throughput = 1.00x; by time
when neither reports a throughput). TARGETS holds the issues' targets by
exact run name. A family with neither a baseline nor a target is listed
under the table.

An end-to-end result (a JSON object with "e2e_cases": [...], written by
bench/e2e.py) adds each whole-process case: its median, the command it
timed, its target with ok/MISS (the VTK baseline measured in the same run).

usage: report.py result.json [result.json ...]
"""
import json
import statistics
import sys

# run name -> (kind, value, issue): "time" is an upper bound in seconds,
# "rate" a lower bound on the throughput in the row's unit.
TARGETS = {
    "BM_ParseMedit_HQView": ("rate", 150.0, "issue 2"),
    "BM_CornerSJ_HQView/2": ("rate", 20.0, "issue 2"),
    "BM_HexMetricsRefined_HQView/2": ("time", 0.3, "issue 3"),
    "BM_GlyphClusters_HQView/1000000/2": ("time", 0.5, "issue 4"),
    "BM_GlyphStage_HQView/1000000/2": ("time", 0.5, "issue 4"),
    "BM_OverlapCertificate_HQView/100/2": ("time", 5.0, "issue 5"),
    "BM_OverlapExhaustive_HQView/47/2/10": ("time", 3.0, "issue 5"),
    "BM_SignedDistance_HQView/2": ("time", 5.0, "issue 6"),
    "BM_WindingSign_HQView": ("time", 5.0, "issue 6"),
    "BM_ReferenceRepair_HQView": ("time", 5.0, "issue 6 stage"),
    "BM_UvAtlas_HQView": ("time", 3.0, "issue 6"),
    "BM_AllViews_Dolphin": ("time", 5.0, "issue 7"),
    "BM_AllViewsPng_Dolphin": ("time", 5.0, "issue 7"),
    "BM_AllViews_Refined": ("time", 15.0, "issue 7"),
    "BM_AllViewsPng_Refined": ("time", 15.0, "issue 7"),
}

SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def canonical(run_name):
    """BM_X/2/iterations:1/repeats:3/real_time -> BM_X/2 (the name in TARGETS)."""
    parts = run_name.split("/")
    return "/".join(p for p in parts if ":" not in p and p not in ("real_time", "process_time", "manual_time"))


def family_of(name):
    parts = name.split("/")[0].split("_")
    return parts[1] if len(parts) >= 2 else name


def is_baseline(name):
    parts = name.split("/")[0].split("_")
    return len(parts) >= 3 and parts[2].startswith("Baseline")


def load(paths):
    """Median rows of the benchmark files, e2e objects, and the programs seen."""
    rows, e2e, programs = [], [], []
    for path in paths:
        with open(path) as f:
            data = json.load(f)
        if "e2e_cases" in data:
            e2e.append(data)
            continue
        programs.append(data.get("context", {}).get("executable", path).split("/")[-1])
        runs = {}
        for b in data["benchmarks"]:
            name = canonical(b["run_name"])
            if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
                continue
            # A benchmark run once has no aggregates: its single run is its median.
            entry = runs.setdefault(name, {"median": None, "single": None, "reps": 0})
            if b.get("aggregate_name") == "median":
                entry["median"] = b
                entry["reps"] = b.get("repetitions", entry["reps"])
            elif b.get("run_type") == "iteration":
                entry["single"] = b
                entry["reps"] += 1
        for name, entry in runs.items():
            b = entry["median"] or entry["single"]
            if b.get("error_occurred"):
                rows.append({"name": name, "error": b.get("error_message", "error")})
                continue
            raw = b.get("bytes_per_second", b.get("items_per_second"))
            if "bytes_per_second" in b:
                rate, unit = b["bytes_per_second"] / 1e6, "MB/s"
            elif "items_per_second" in b:
                rate, unit = b["items_per_second"] / 1e6, "M items/s"
                if rate < 1:
                    rate, unit = rate * 1e3, "k items/s"
            else:
                rate, unit = None, ""
            seconds = b["real_time"] * SECONDS[b["time_unit"]]
            label = name + (" [" + b["label"] + "]" if b.get("label") else "")
            rows.append({"name": name, "label": label, "seconds": seconds, "time": b["real_time"],
                         "unit": b["time_unit"], "rate": rate, "raw_rate": raw, "rate_unit": unit, "reps": entry["reps"]})
    return rows, e2e, programs


def target_text(kind, value, unit, measured):
    if kind == "time":
        ok = measured <= value
        return "< %g s" % value, ok
    ok = measured >= value
    return ">= %g %s" % (value, unit), ok


def main():
    rows, e2e, programs = load(sys.argv[1:])
    baselines = {}
    for r in rows:
        if "error" not in r and is_baseline(r["name"]):
            baselines.setdefault(family_of(r["name"]), r)

    fmt = "%-52s %12s %14s %26s %22s"
    reps = sorted({r["reps"] for r in rows if "reps" in r})
    print(fmt % ("benchmark (median of %s)" % "/".join(map(str, reps)), "time", "throughput",
                 "vs baseline (same run)", "target"))
    missing, misses = [], []
    for r in rows:
        if "error" in r:
            print("%-52s ERROR: %s" % (r["name"], r["error"]))
            misses.append(r["name"])
            continue
        family = family_of(r["name"])
        base = baselines.get(family)
        if base is r:
            vs = "1.00x (baseline)"
        elif base and r["raw_rate"] and base["raw_rate"]:
            vs = "%.2fx %s" % (r["raw_rate"] / base["raw_rate"], base["name"].split("_")[2].split("/")[0])
        elif base:
            vs = "%.2fx %s" % (base["seconds"] / r["seconds"], base["name"].split("_")[2].split("/")[0])
        else:
            vs = "-"
        target = "-"
        if r["name"] in TARGETS:
            kind, value, issue = TARGETS[r["name"]]
            text, ok = target_text(kind, value, r["rate_unit"], r["seconds"] if kind == "time" else r["rate"] or 0)
            target = "%s %s (%s)" % (text, "ok" if ok else "MISS", issue)
            if not ok:
                misses.append(r["name"])
        if base is None and not any(x["name"] in TARGETS for x in rows if family_of(x["name"]) == family):
            if family not in missing:
                missing.append(family)
        tp = "%.1f %s" % (r["rate"], r["rate_unit"]) if r["rate"] else "-"
        print(fmt % (r["label"][:52], "%.3f %s" % (r["time"], r["unit"]), tp, vs, target))

    # The whole process (bench/e2e.py): each case with the command it timed.
    for e in e2e:
        print()
        print("end to end (issue 20), medians; every command is printed under its figure:")
        for c in e["e2e_cases"]:
            runs = ", ".join("%.2f" % r for r in c["runs"])
            print("  %-66s %9.2f %-2s  %s%s" % (c["label"], c["value"], c["unit"], c["target"],
                                                "" if c["target"] == "baseline" else (" ok" if c["ok"] else " MISS")))
            print("      $ %s%s" % (c["command"], "   (runs: %s)" % runs if runs else ""))
            if not c["ok"]:
                misses.append(c["label"])
        print("  load average after the e2e runs: %s" % " ".join("%.2f" % x for x in e["load_average"]))

    print()
    print("programs: %s" % ", ".join(programs))
    if missing:
        print("no baseline and no target: %s" % ", ".join(missing))
    if misses:
        print("missed: %s" % ", ".join(misses))


if __name__ == "__main__":
    main()
