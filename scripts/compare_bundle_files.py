#!/usr/bin/env python3
"""Compares two output trees of HQView (scripts/compare-bundles' base/out and
new/out) file by file, aware of JSON, CSV and VTU, after removing exactly the
keys, columns and arrays that an additions file lists as added or changed on
purpose.

  compare_bundle_files.py --additions FILE [--changelog CHANGELOG.md] BASE NEW

FILE (JSON) lists the changes made on purpose since a base commit:

  {"base": "5dd2bb2",
   "entries": [
     {"files": "report.json", "json": "glyphs.clusters[*].tie_class",
      "change": "added", "issue": "44 part T",
      "changelog": "new keys `glyphs.tie_tolerance`, `glyphs.clusters[].tie_class`"},
     {"files": "data/cells.csv", "column": "source_index", ...},
     {"files": "data/annotated.vtu", "array": "source_index", ...}]}

`files` is a glob matched against each file's path relative to the tree
(`report.json` matches every report.json at any depth). A JSON path is dotted
keys, `[*]` (every element of an array), `*` (every key of an object),
`[N]`, `[?key=glob]` (the elements whose `key` matches) and
`["a key.with dots"]`; a key segment is a glob (`["quality.by_kind.*"]`). `change` is `added` (absent in the base,
present in the new output wherever its parent is), `changed` (present on both
sides, its value changed on purpose) or `removed` (present in the base only).
A `changed` entry that some runs leave equal says why in `may_be_unchanged`
(then it is a note, not a finding). `changelog` is a quote of CHANGELOG.md (compared with whitespace collapsed):
each entry must be justified there (checked with --changelog).

What is compared, after the listed paths are removed from both sides:
report.json, index.json and every other .json but timings.json (wall
times): parsed, numbers as values (an unchanged number must be equal, not
close), keys in order; .csv files: the columns by name, in order, every cell
(numbers as parsed values, else text); .vtu files: the Piece's counts and
every DataArray by section and name (type, components, decompressed values
bit for bit); any other file not skipped: bytes. Skipped, and said so: pages
and pictures (.html, .md, .tex, .png, .svg, .css, the viewer's .js, `hqview
diff`'s .txt output), which the picture and page issues change on purpose and
no filter can isolate; timings.json; junit.xml (index.json's rows as test
cases, compared through index.json).

Reported, each with its path: every remaining difference, a file on one side
only, an `added` path absent from the new output where its parent exists (or
present in the base), a `removed` path still in the new output, a `changed`
path that was equal in every file it was found in (over-broad), and an entry
whose changelog quote is not in CHANGELOG.md. Exit 0 when nothing is
reported, 1 otherwise, 2 on bad usage or an unreadable additions file.
"""
import argparse
import csv
import fnmatch
import json
import math
import os
import re
import struct
import sys
import zlib

SKIPPED_SUFFIXES = {
    ".html": "pages (issues 44, 45, 47 changed their text and layout on purpose)",
    ".md": "pages (summary.md, comparison.md: page text changed by issues 45, 46, 47)",
    ".tex": "pages (comparison.tex)",
    ".png": "pictures (issues 44, 45, 46, 47, 48 changed the views on purpose)",
    ".svg": "pictures (the charts)",
    ".css": "the pages' stylesheet",
    ".js": "the viewer (issue 44 and 46 changed its drawing and data.js colours)",
    ".txt": "hqview diff's text output (issue 45 added the side-by-side table, 46 the composition rows)",
}
SKIPPED_NAMES = {
    "timings.json": "wall times, different on every run by design",
    "junit.xml": "index.json's rows and gates as test cases (issue 47 part D's skipped rows add cases): "
                 "compared through index.json",
}
MAX_SHOWN = 20  # differences printed per file; the rest are counted


class Entry:
    def __init__(self, raw, index):
        self.raw = raw
        self.index = index
        self.files = raw["files"]
        self.change = raw.get("change", "added")
        if self.change not in ("added", "changed", "removed"):
            raise ValueError("entry %d: change must be added, changed or removed" % index)
        kinds = [k for k in ("json", "column", "array") if k in raw]
        if len(kinds) != 1:
            raise ValueError("entry %d: exactly one of json, column, array" % index)
        self.kind = kinds[0]
        self.target = raw[self.kind]
        self.pattern = parse_path(self.target) if self.kind == "json" else None
        for field in ("issue", "changelog"):
            if not raw.get(field):
                raise ValueError("entry %d (%s): no %s" % (index, self.target, field))
        self.found = 0      # files in which it matched something
        self.differed = 0   # files in which its removed values differed (changed)

    def applies_to(self, rel):
        return fnmatch.fnmatchcase(rel, self.files) or fnmatch.fnmatchcase(rel, "*/" + self.files)

    def name(self):
        return "%s %s (%s, issue %s)" % (self.kind, self.target, self.change, self.raw["issue"])


# ---------------------------------------------------------------- JSON paths

PATH_TOKEN = re.compile(r'\.?([^.\[\]"]+)|\[(\*|\d+|\?[^\]=]+=[^\]]*)\]|\["((?:[^"\\]|\\.)*)"\]')


def parse_path(text):
    """'a.b[*]["c.d"].*' -> ['a', 'b', '[*]', 'c.d', '*']; '[N]' stays '[N]'."""
    segments, pos = [], 0
    while pos < len(text):
        m = PATH_TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise ValueError("bad JSON path %r at %d" % (text, pos))
        if m.group(1) is not None:
            segments.append(m.group(1))
        elif m.group(2) is not None:
            segments.append("[" + m.group(2) + "]")
        else:
            segments.append(json.loads('"' + m.group(3) + '"'))
        pos = m.end()
    return segments


def key_text(key):
    return key if re.fullmatch(r"[A-Za-z0-9_<>-]+", key) else json.dumps(key)


def child_path(path, key):
    if isinstance(key, int):
        return "%s[%d]" % (path, key)
    if re.fullmatch(r"[A-Za-z0-9_<>-]+", key):
        return key if not path else path + "." + key
    return '%s[%s]' % (path, json.dumps(key))


def segment_matches(segment, key, value=None):
    """A key segment is a glob (`*`, `quality.by_kind.*`); an element segment
    `[*]`, `[N]` or `[?key=glob]` (the elements whose key matches the glob)."""
    if isinstance(key, int):
        if segment.startswith("[?"):
            name, _, text = segment[2:-1].partition("=")
            return isinstance(value, dict) and name in value and fnmatch.fnmatchcase(str(value[name]), text)
        return segment == "[*]" or segment == "[%d]" % key
    return not segment.startswith("[") and fnmatch.fnmatchcase(key, segment)


def strip(node, patterns, hits, removed):
    """Returns node without the subtrees the patterns (lists of segments with
    their entry) name; hits[entry] counts matches; removed[entry] collects the
    removed values by concrete path."""
    return _strip(node, [(p, e) for e, p in patterns], "", hits, removed)


def _strip(node, live, path, hits, removed):
    if not live or not isinstance(node, (dict, list)):
        return node
    items = node.items() if isinstance(node, dict) else enumerate(node)
    kept = {} if isinstance(node, dict) else []
    for key, value in items:
        sub = []
        drop = False
        for pattern, entry in live:
            if segment_matches(pattern[0], key, value):
                if len(pattern) == 1:
                    drop = True
                    hits[entry] = hits.get(entry, 0) + 1
                    removed.setdefault(entry, {})[child_path(path, key)] = value
                else:
                    sub.append((pattern[1:], entry))
        if drop:
            continue
        value = _strip(value, sub, child_path(path, key), hits, removed)
        if isinstance(kept, dict):
            kept[key] = value
        else:
            kept.append(value)
    return kept


def parents_missing(node, pattern):
    """Concrete paths of the nodes the pattern's parent names that lack its
    last segment (an addition absent where it belongs)."""
    missing = []

    def walk(value, segments, path):
        if len(segments) == 1:
            last = segments[0]
            if isinstance(value, dict) and not any(c in last for c in "*?[") and last not in value:
                missing.append(child_path(path, last))
            elif isinstance(value, list) and re.fullmatch(r"\[\d+\]", last):
                if int(last[1:-1]) >= len(value):
                    missing.append(path + last)
            elif value is not None and not isinstance(value, (dict, list)):  # null: a stage that did not run
                missing.append(child_path(path, last) if not last.startswith("[") else path + last)
            return
        if isinstance(value, dict):
            for k, v in value.items():
                if segment_matches(segments[0], k, v):
                    walk(v, segments[1:], child_path(path, k))
        elif isinstance(value, list):
            for i, v in enumerate(value):
                if segment_matches(segments[0], i, v):
                    walk(v, segments[1:], child_path(path, i))

    walk(node, pattern, "")
    return missing


def value_kind(v):
    if isinstance(v, bool):
        return "bool"
    if isinstance(v, (int, float)):
        return "number"
    if v is None:
        return "null"
    if isinstance(v, str):
        return "string"
    return "array" if isinstance(v, list) else "object"


def same_number(a, b):
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b


def short(v):
    text = json.dumps(v)
    return text if len(text) <= 80 else text[:77] + "..."


def json_differences(a, b, path, out):
    ka, kb = value_kind(a), value_kind(b)
    if ka != kb:
        out.append("%s: %s -> %s" % (path or "(root)", short(a), short(b)))
    elif ka == "object":
        for key in a:
            if key not in b:
                out.append("%s: removed (was %s)" % (child_path(path, key), short(a[key])))
        for key in b:
            if key not in a:
                out.append("%s: added (%s)" % (child_path(path, key), short(b[key])))
        common_a = [k for k in a if k in b]
        common_b = [k for k in b if k in a]
        if common_a != common_b:
            out.append("%s: keys in another order: %s -> %s" % (path or "(root)", short(common_a), short(common_b)))
        for key in common_a:
            json_differences(a[key], b[key], child_path(path, key), out)
    elif ka == "array":
        if len(a) != len(b):
            out.append("%s: %d elements -> %d" % (path or "(root)", len(a), len(b)))
        for i in range(min(len(a), len(b))):
            json_differences(a[i], b[i], child_path(path, i), out)
    elif ka == "number":
        if not same_number(a, b):
            out.append("%s: %s -> %s" % (path, short(a), short(b)))
    elif a != b:
        out.append("%s: %s -> %s" % (path, short(a), short(b)))


def compare_json(base_file, new_file, entries):
    with open(base_file, "rb") as f:
        a = json.loads(f.read().decode("utf-8"))
    with open(new_file, "rb") as f:
        b = json.loads(f.read().decode("utf-8"))
    mine = [e for e in entries if e.kind == "json"]
    patterns = [(e, e.pattern) for e in mine]
    hits_a, hits_b, removed_a, removed_b = {}, {}, {}, {}
    sa = strip(a, patterns, hits_a, removed_a)
    sb = strip(b, patterns, hits_b, removed_b)
    out = []
    for e in mine:
        if hits_b.get(e, 0) or hits_a.get(e, 0):
            e.found += 1
        if e.change == "added":
            for p in parents_missing(b, e.pattern):
                out.append("%s: listed addition absent from the new output (%s)" % (p, e.name()))
            if hits_a.get(e, 0):
                out.append("%s: listed addition already in the base (%s)" % (sorted(removed_a[e])[0], e.name()))
        elif e.change == "removed":
            if hits_b.get(e, 0):
                out.append("%s: listed removal still in the new output (%s)" % (sorted(removed_b[e])[0], e.name()))
        else:
            ra, rb = removed_a.get(e, {}), removed_b.get(e, {})
            for p in parents_missing(b, e.pattern):
                out.append("%s: listed change absent from the new output (%s)" % (p, e.name()))
            for p in sorted(set(ra) - set(rb)):
                out.append("%s: listed change absent from the new output (%s)" % (p, e.name()))
            diffs = []
            for p in ra:
                if p in rb:
                    json_differences(ra[p], rb[p], p, diffs)
            if diffs or set(rb) - set(ra):
                e.differed += 1
    json_differences(sa, sb, "", out)
    return out


# ---------------------------------------------------------------- CSV

def check_named(entry, in_base, in_new, differs, out):
    """A listed CSV column or VTU array: present where its change says
    (reported in out), and counted as found and, for a change, as differing."""
    what = "%s %s" % ("column" if entry.kind == "column" else "array", entry.target)
    if in_base or in_new:
        entry.found += 1
    if entry.change == "added":
        if not in_new:
            out.append("%s: listed addition absent from the new output (%s)" % (what, entry.name()))
        if in_base:
            out.append("%s: listed addition already in the base (%s)" % (what, entry.name()))
    elif entry.change == "removed":
        if in_new:
            out.append("%s: listed removal still in the new output (%s)" % (what, entry.name()))
    elif not in_base or not in_new:
        out.append("%s: listed change not on both sides (%s)" % (what, entry.name()))
    elif differs():
        entry.differed += 1


def column_differs(name, ha, ra, hb, rb):
    ia, ib = ha.index(name), hb.index(name)
    return len(ra) != len(rb) or any(x[ia] != y[ib] for x, y in zip(ra, rb))

def as_number(text):
    try:
        return float(text)
    except ValueError:
        return None


def compare_csv(base_file, new_file, entries):
    def read(path):
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
        return (rows[0] if rows else []), rows[1:]

    ha, ra = read(base_file)
    hb, rb = read(new_file)
    mine = [e for e in entries if e.kind == "column"]
    out = []
    listed = set()
    for e in mine:
        listed.add(e.target)
        check_named(e, e.target in ha, e.target in hb, lambda e=e: column_differs(e.target, ha, ra, hb, rb), out)
    keep_a = [i for i, c in enumerate(ha) if c not in listed]
    keep_b = [i for i, c in enumerate(hb) if c not in listed]
    names_a, names_b = [ha[i] for i in keep_a], [hb[i] for i in keep_b]
    if names_a != names_b:
        out.append("header: %s -> %s" % (",".join(names_a), ",".join(names_b)))
        return out
    if len(ra) != len(rb):
        out.append("rows: %d -> %d" % (len(ra), len(rb)))
    for r, (x, y) in enumerate(zip(ra, rb)):
        if len(x) != len(ha) or len(y) != len(hb):
            out.append("row %d: %d fields -> %d (header %d, %d)" % (r + 1, len(x), len(y), len(ha), len(hb)))
            continue
        for name, i, j in zip(names_a, keep_a, keep_b):
            u, v = x[i], y[j]
            if u == v:
                continue
            nu, nv = as_number(u), as_number(v)
            if nu is not None and nv is not None and same_number(nu, nv):
                continue
            out.append("row %d (%s %s), column %s: %s -> %s" % (r + 1, ha[0], x[0], name, u, v))
    return out


# ---------------------------------------------------------------- VTU

VTU_TYPES = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i", "UInt8": "B", "UInt64": "Q", "Int8": "b"}


def read_vtu(path):
    """{(section, name): (type, components, bytes)} and the Piece's counts."""
    with open(path, "rb") as f:
        data = f.read()
    start = data.index(b"<AppendedData")
    underscore = data.index(b"_", data.index(b">", start)) + 1
    header = data[:start].decode("utf-8")
    compressed = 'compressor="vtkZLibDataCompressor"' in header
    if 'header_type="UInt64"' not in header:
        raise ValueError("%s: not a UInt64-header VTU" % path)
    piece = re.search(r'<Piece NumberOfPoints="(\d+)" NumberOfCells="(\d+)"', header)
    arrays = {}
    section = None
    for m in re.finditer(r"<(/?)(PointData|CellData|Points|Cells)\b|<DataArray ([^>]*)/>", header):
        if m.group(2):
            section = None if m.group(1) else m.group(2)
            continue
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(3)))
        offset = underscore + int(attrs["offset"])
        if compressed:
            (blocks,) = struct.unpack_from("<Q", data, offset)
            _, _, _, *sizes = struct.unpack_from("<%dQ" % (blocks + 3), data, offset)
            pos = offset + 8 * (blocks + 3)
            raw = bytearray()
            for size in sizes:
                raw += zlib.decompress(data[pos:pos + size])
                pos += size
            raw = bytes(raw)
        else:
            (size,) = struct.unpack_from("<Q", data, offset)
            raw = data[offset + 8:offset + 8 + size]
        arrays[(section, attrs["Name"])] = (attrs["type"], int(attrs.get("NumberOfComponents", "1")), raw)
    return (piece.group(1), piece.group(2)) if piece else None, arrays


def compare_vtu(base_file, new_file, entries):
    piece_a, aa = read_vtu(base_file)
    piece_b, ab = read_vtu(new_file)
    mine = [e for e in entries if e.kind == "array"]
    out = []
    if piece_a != piece_b:
        out.append("Piece NumberOfPoints, NumberOfCells: %s -> %s" % (piece_a, piece_b))
    listed = set()
    for e in mine:
        keys_a = [k for k in aa if k[1] == e.target]
        keys_b = [k for k in ab if k[1] == e.target]
        listed.update(keys_a + keys_b)
        check_named(e, bool(keys_a), bool(keys_b), lambda ka=keys_a: any(aa[k] != ab.get(k) for k in ka), out)
    order_a = [k for k in aa if k not in listed]
    order_b = [k for k in ab if k not in listed]
    if order_a != order_b:
        out.append("arrays: %s -> %s" % (["%s/%s" % k for k in order_a], ["%s/%s" % k for k in order_b]))
    for key in order_a:
        if key not in ab:
            continue
        (ta, ca, da), (tb, cb, db) = aa[key], ab[key]
        where = "%s/%s" % key
        if (ta, ca) != (tb, cb):
            out.append("%s: %s x%d -> %s x%d" % (where, ta, ca, tb, cb))
            continue
        if da == db:
            continue
        code = VTU_TYPES.get(ta)
        if code is None or len(da) != len(db):
            out.append("%s: %d bytes -> %d" % (where, len(da), len(db)))
            continue
        size = struct.calcsize(code)
        va = struct.unpack("<%d%s" % (len(da) // size, code), da)
        vb = struct.unpack("<%d%s" % (len(db) // size, code), db)
        bad = [i for i in range(len(va)) if not (va[i] == vb[i] or (va[i] != va[i] and vb[i] != vb[i]))]
        if not bad:  # only -0.0 against 0.0, or NaN payloads
            out.append("%s: equal values, other bytes" % where)
        for i in bad[:MAX_SHOWN]:
            out.append("%s[%d] (tuple %d): %r -> %r" % (where, i, i // ca, va[i], vb[i]))
        if len(bad) > MAX_SHOWN:
            out.append("%s: %d values differ in all" % (where, len(bad)))
    return out


# ---------------------------------------------------------------- the trees

def skip_reason(rel):
    name = os.path.basename(rel)
    if name in SKIPPED_NAMES:
        return SKIPPED_NAMES[name]
    for suffix, reason in SKIPPED_SUFFIXES.items():
        if name.endswith(suffix):
            return reason
    return None


def kind_of(rel):
    if rel.endswith(".json"):
        return "json"
    if rel.endswith(".csv"):
        return "csv"
    if rel.endswith(".vtu"):
        return "vtu"
    return "bytes"


def list_files(root):
    files = []
    for dirpath, _, names in os.walk(root):
        for n in names:
            files.append(os.path.relpath(os.path.join(dirpath, n), root).replace(os.sep, "/"))
    return sorted(files)


def normalise(text):
    return " ".join(text.split())


def load_entries(path, changelog):
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    entries = [Entry(raw, i) for i, raw in enumerate(doc["entries"])]
    problems = []
    if changelog:
        with open(changelog, encoding="utf-8") as f:
            text = normalise(f.read())
        for e in entries:
            if normalise(e.raw["changelog"]) not in text:
                problems.append("additions: %s: its changelog quote is not in %s: %s"
                                % (e.name(), changelog, short(e.raw["changelog"])))
    return entries, problems


def compare_trees(base, new, entries):
    """Prints a table per mode (first directory level) and returns the
    reported lines."""
    files_a, files_b = list_files(base), list_files(new)
    reported = []
    only_a = sorted(set(files_a) - set(files_b))
    only_b = sorted(set(files_b) - set(files_a))
    for rel in only_a:
        if not skip_reason(rel):
            reported.append("%s: in the base only" % rel)
    for rel in only_b:
        if not skip_reason(rel):
            reported.append("%s: in the new output only" % rel)
    stats = {}
    skipped = {}
    for rel in sorted(set(files_a) & set(files_b)):
        mode = rel.split("/", 1)[0]
        row = stats.setdefault(mode, [0, 0, 0])
        reason = skip_reason(rel)
        if reason:
            row[2] += 1
            skipped.setdefault(reason, 0)
            skipped[reason] += 1
            continue
        row[0] += 1
        applying = [e for e in entries if e.applies_to(rel)]
        a, b = os.path.join(base, rel), os.path.join(new, rel)
        kind = kind_of(rel)
        try:
            if kind == "json":
                diffs = compare_json(a, b, applying)
            elif kind == "csv":
                diffs = compare_csv(a, b, applying)
            elif kind == "vtu":
                diffs = compare_vtu(a, b, applying)
            else:
                with open(a, "rb") as fa, open(b, "rb") as fb:
                    diffs = [] if fa.read() == fb.read() else ["bytes differ"]
        except (ValueError, KeyError, struct.error, zlib.error, UnicodeDecodeError) as err:
            diffs = ["cannot be compared: %s" % err]
        if diffs:
            row[1] += 1
            for d in diffs[:MAX_SHOWN]:
                reported.append("%s: %s" % (rel, d))
            if len(diffs) > MAX_SHOWN:
                reported.append("%s: ... %d differences in all" % (rel, len(diffs)))
    print("%-14s %8s %8s %8s" % ("mode", "compared", "differ", "skipped"))
    total = [0, 0, 0]
    for mode in sorted(stats):
        row = stats[mode]
        print("%-14s %8d %8d %8d" % (mode, row[0], row[1], row[2]))
        total = [t + r for t, r in zip(total, row)]
    print("%-14s %8d %8d %8d" % ("all", total[0], total[1], total[2]))
    for reason in sorted(skipped):
        print("skipped: %d files: %s" % (skipped[reason], reason))
    for e in entries:
        if e.change == "changed" and e.found and not e.differed:
            if e.raw.get("may_be_unchanged"):
                print("note: %s: equal on both sides in the %d files it was found in (%s)"
                      % (e.name(), e.found, e.raw["may_be_unchanged"]))
            else:
                reported.append("additions: %s: found in %d files, equal on both sides in every one (over-broad)"
                                % (e.name(), e.found))
        if not e.found and e.change != "added":
            print("note: %s: in no compared file (not exercised by this run)" % e.name())
    return reported, total


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--additions", required=True, help="the JSON list of changes made on purpose")
    parser.add_argument("--changelog", help="CHANGELOG.md: every entry's quote must be in it")
    parser.add_argument("base")
    parser.add_argument("new")
    args = parser.parse_args(argv)
    try:
        entries, problems = load_entries(args.additions, args.changelog)
    except (OSError, ValueError, KeyError) as err:
        print("compare_bundle_files: %s: %s" % (args.additions, err), file=sys.stderr)
        return 2
    for d in (args.base, args.new):
        if not os.path.isdir(d):
            print("compare_bundle_files: no directory %s" % d, file=sys.stderr)
            return 2
    reported, total = compare_trees(args.base, args.new, entries)
    reported = problems + reported
    for line in reported:
        print("  differs: " + line)
    if total[0] == 0:
        print("compare_bundle_files: no file compared")
        return 1
    if reported:
        print("compare_bundle_files: %d differences outside the listed additions" % len(reported))
        return 1
    print("compare_bundle_files: no difference outside the listed additions (%d files compared)" % total[0])
    return 0


if __name__ == "__main__":
    sys.exit(main())
