"""The keys of HQView's JSON outputs, normalised as docs/contract.md lists
them (shared by check_contract.py)."""
import json

STATS_KEYS = {"count", "min", "max", "mean", "std", "p01", "p05", "p50", "p95", "p99", "histogram"}


def is_stats(value):
    return isinstance(value, dict) and STATS_KEYS <= set(value)


def dotted_paths(document, rule):
    """Every leaf's dotted path; an array of objects is `path[]` (listed
    itself, then its objects' keys). rule(path, value) may claim a node:
    it returns the paths that stand for it (the walk does not go below), or
    None to walk on."""
    keys = set()

    def walk(value, path):
        claimed = rule(path, value)
        if claimed is not None:
            keys.update(claimed)
        elif isinstance(value, dict):
            for k, v in value.items():
                walk(v, f"{path}.{k}" if path else k)
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            keys.add(path + "[]")
            for v in value:
                walk(v, path + "[]")
        else:
            keys.add(path)

    walk(document, "")
    return keys


def report_rule(path, value):
    """report.json: each statistics object is one path (its members are
    listed once, by stats_keys()); compare.headline, compare.mesh and
    compare.quality one path each (their members must be those of the
    top-level headline, mesh and quality: compare_mirrors()); the metric
    names under quality.metrics are `<metric>`, quality.by_kind's
    `<kind>.<member>` and `<kind>.metrics.<name>`, the keys of
    compare.differences `<key>`."""
    if is_stats(value) or path in ("compare.headline", "compare.mesh", "compare.quality"):
        return {path}
    if path == "compare.differences" and isinstance(value, dict):
        return {path + ".<key>"}
    if (path.startswith("structure.singular_edges_by_valence.")
            or path.startswith("structure.irregular_vertices_by_valence.")) and isinstance(value, dict):
        return {path + ".<valence>"}
    if path in ("fem.poisson.correlation", "fem.poisson.correlation_given_size",
                "fem.poisson.correlation_interval", "fem.poisson.correlation_interval_adjusted") and isinstance(value, dict):
        return {path + ".<metric>"} if value else set()
    if path == "fem.poisson.solutions" and isinstance(value, dict):
        return {f"{path}.<solution>.{k}" for v in value.values() for k in v}
    if path == "quality.by_kind" and isinstance(value, dict):
        keys = {path}
        for v in value.values():
            for k, member in v.items():
                keys.add(f"{path}.<kind>.metrics.<name>" if k == "metrics" else f"{path}.<kind>.{k}")
        return keys
    if path.endswith("quality.metrics") and isinstance(value, dict):
        return {path + ".<metric>"} if value else set()
    return None


def report_keys(report):
    return dotted_paths(report, report_rule)


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
    """index.json: a mesh's headline keys are dotted report.json paths
    themselves, listed as they are."""
    def rule(path, value):
        if path == "meshes[].headline" and isinstance(value, dict):
            return {path + "." + k for k in value}
        if path == "methods[].keys" and isinstance(value, dict):
            return {path + ".<key>." + member for v in value.values() for member in v}
        if path == "meshes[].metrics" and isinstance(value, dict):  # per metric name (--simulate)
            return {path + ".<metric>." + member for v in value.values() for member in v}
        if path == "methods[].fem_correlation" and isinstance(value, dict):  # documented as fem_correlation
            return {path}
        return None

    return dotted_paths(index, rule)


def null_paths(document):
    """The dotted paths whose value is null."""
    found = set()

    def walk(value, path):
        if value is None:
            found.add(path)
        elif isinstance(value, dict):
            for k, v in value.items():
                walk(v, f"{path}.{k}" if path else k)

    walk(document, "")
    return found


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)
