#!/usr/bin/env python3
"""--link-base (issue 21): every link of index.html, boundary.html and
summary.md (and of the batch pages: index.html, summary.md, comparison.md)
is absolute under the URL and names a file that exists in the bundle; the
bundle's summary.md shows the key view inline; without the flag no link is
absolute; a URL that is not http(s)/file, or holds a quote, is exit 2.

usage: check_links.py HQVIEW SOURCE_DIR WORKDIR
"""
import re
import shutil
import subprocess
import sys
from pathlib import Path
from urllib.parse import unquote

FAILURES = []
BASE = "https://example.org/ci/run-7/"


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        FAILURES.append(what)


def links(path):
    text = path.read_text()
    if path.suffix == ".md":
        return re.findall(r"\]\(([^)]*)\)", text)
    return re.findall(r' (?:href|src)="([^"]*)"', text)


def check_absolute(page, root, base):
    """Every link of page (but in-page anchors) under base, naming a file below root."""
    bad = []
    for target in links(page):
        if target.startswith("#"):
            continue
        if not target.startswith(base):
            bad.append(target)
            continue
        rel = unquote(target[len(base):].split("#")[0])
        if not (root / rel).is_file():
            bad.append(target)
    check(not bad and links(page), f"{page.relative_to(root.parent)}: {len(links(page))} links, all absolute and existing"
          + (f" (bad: {bad[:4]})" if bad else ""))


def main():
    hq, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3]).resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    ex = source / "examples"
    # One bundle with every page.
    out = work / "bundle"
    r = subprocess.run([hq, "analyze", str(ex / "ball.mesh"), "--reference", str(ex / "ball.off"), "-o", str(out),
                        "--quiet", "--size", "320x240", "--link-base", BASE.rstrip("/")])
    check(r.returncode == 0, f"analyze --link-base: exit {r.returncode}")
    for page in ["index.html", "boundary.html", "summary.md"]:
        check_absolute(out / page, out, BASE)
    summary = (out / "summary.md").read_text()
    check(re.search(r"^!\[[^\]]*\]\(" + re.escape(BASE) + r"views/main_1\.png\)$", summary, re.M) is not None,
          "summary.md shows the key view (A) inline")
    # A batch over a folder with a space and a '#': links encoded, bundles under BASE + path.
    coll = work / "collection"
    (coll / "my meshes#1").mkdir(parents=True)
    shutil.copy(ex / "ball.mesh", coll / "my meshes#1" / "ball.mesh")
    shutil.copy(ex / "twisted_bar.mesh", coll / "twisted_bar.mesh")
    manifest = coll / "manifest.csv"
    manifest.write_text("mesh,label\nmy meshes#1/ball.mesh,alpha\ntwisted_bar.mesh,beta\n")
    bout = work / "batch"
    r = subprocess.run([hq, "batch", str(manifest), "-o", str(bout), "--quiet", "--no-render", "--link-base", BASE])
    check(r.returncode in (0, 1), f"batch --link-base: exit {r.returncode}")
    for page in ["index.html", "summary.md", "comparison.md"]:
        check_absolute(bout / page, bout, BASE)
    bundle = bout / "my meshes#1" / "ball.mesh"
    bundle_base = BASE + "my%20meshes%231/ball.mesh/"
    for page in ["index.html", "summary.md"]:
        check_absolute(bundle / page, bundle, bundle_base)
    # Without the flag: relative links only.
    plain = work / "plain"
    subprocess.run([hq, "analyze", str(ex / "ball.mesh"), "-o", str(plain), "--quiet", "--no-render"])
    absolute = [t for p in ["index.html", "summary.md"] for t in links(plain / p) if "://" in t]
    check(not absolute, f"without --link-base every link is relative ({absolute[:3]})")
    for bad in ["ftp://example.org/x", "example.org/x", 'https://example.org/"x', "https://example.org/a b"]:
        r = subprocess.run([hq, "analyze", str(ex / "ball.mesh"), "-o", str(work / "bad"), "--no-render",
                            "--link-base", bad], capture_output=True, text=True)
        check(r.returncode == 2 and "--link-base" in r.stderr and not (work / "bad").exists(),
              f"--link-base '{bad}': exit {r.returncode} (want 2), nothing written")
    print(f"{len(FAILURES)} failed" if FAILURES else "all link checks passed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
