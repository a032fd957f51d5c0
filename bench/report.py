#!/usr/bin/env python3
"""Prints the medians of Google Benchmark JSON results and each benchmark's
ratio to the baseline of its family measured in the same run.

A benchmark named BM_<Family>_HQView[/arg] is compared with
BM_<Family>_Baseline<Anything> (the baseline's throughput = 1.0x).
usage: report.py result.json [result.json ...]
"""
import json
import sys


def medians(paths):
    rows = []
    for path in paths:
        with open(path) as f:
            data = json.load(f)
        for b in data["benchmarks"]:
            if b.get("aggregate_name") != "median":
                continue
            name = b["run_name"]
            if "bytes_per_second" in b:
                rate, unit = b["bytes_per_second"] / 1e6, "MB/s"
            elif "items_per_second" in b:
                rate, unit = b["items_per_second"] / 1e6, "M items/s"
            else:
                rate, unit = None, ""
            rows.append((name, b["real_time"], b["time_unit"], rate, unit))
    return rows


def main():
    rows = medians(sys.argv[1:])
    baselines = {}
    for name, _, _, rate, _ in rows:
        parts = name.split("/")[0].split("_")
        if len(parts) >= 3 and parts[2].startswith("Baseline") and rate:
            baselines[parts[1]] = rate
    print("%-44s %14s %14s %10s" % ("benchmark (median)", "time", "throughput", "vs base"))
    for name, time, unit, rate, rate_unit in rows:
        family = name.split("/")[0].split("_")[1]
        ratio = "%.2fx" % (rate / baselines[family]) if rate and family in baselines else "-"
        tp = "%.1f %s" % (rate, rate_unit) if rate else "-"
        print("%-44s %11.3f %-2s %14s %10s" % (name, time, unit, tp, ratio))


if __name__ == "__main__":
    main()
