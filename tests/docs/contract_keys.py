"""The keys of HQView's JSON outputs and CSV headers, normalised as
docs/contract.md lists them (shared by check_contract.py)."""
import json

STATS_KEYS = {"count", "min", "max", "mean", "std", "p01", "p05", "p50", "p95", "p99", "histogram"}


def is_stats(value):
    return isinstance(value, dict) and STATS_KEYS <= set(value)


def report_keys(report):
    """Dotted paths of a report.json: arrays of objects as `[]`, the metric
    names under quality.metrics as `<metric>`, the keys of
    compare.differences as `<key>`, each statistics object as one path
    (its members are listed once, by stats_keys()), and compare.headline,
    compare.mesh and compare.quality as one path each (their members must be
    those of the top-level headline, mesh and quality: compare_mirrors())."""
    keys = set()

    def walk(value, path):
        if is_stats(value) or path in ("compare.headline", "compare.mesh", "compare.quality"):
            keys.add(path)
            return
        if isinstance(value, dict):
            if path.endswith("quality.metrics"):
                for v in value.values():
                    walk(v, path + ".<metric>")
                return
            if path == "compare.differences":
                keys.add("compare.differences.<key>")
                return
            for k, v in value.items():
                walk(v, f"{path}.{k}" if path else k)
            return
        if isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            keys.add(path + "[]")
            for v in value:
                walk(v, path + "[]")
            return
        keys.add(path)

    walk(report, "")
    return keys


def compare_mirrors(report):
    """The paths under compare.headline/mesh/quality that the top-level
    headline/mesh/quality lacks (should be none)."""
    if not isinstance(report.get("compare"), dict):
        return set()
    stray = set()
    for part in ("headline", "mesh", "quality"):
        theirs = report_keys({part: report["compare"][part]})
        mine = report_keys({part: report[part]})
        stray |= {"compare." + k for k in theirs - mine}
    return stray


def stats_keys(report):
    found = set()

    def walk(value):
        if is_stats(value):
            found.update(value.keys())
        if isinstance(value, dict):
            for v in value.values():
                walk(v)
        elif isinstance(value, list):
            for v in value:
                walk(v)

    walk(report)
    return {"<stats>." + k for k in found}


def index_keys(index):
    keys = set()

    def walk(value, path):
        if isinstance(value, dict):
            if path == "meshes[].headline":
                for k in value:
                    keys.add(path + "." + k)
                return
            for k, v in value.items():
                walk(v, f"{path}.{k}" if path else k)
            return
        if isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            keys.add(path + "[]")
            for v in value:
                walk(v, path + "[]")
            return
        keys.add(path)

    walk(index, "")
    return keys


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)
