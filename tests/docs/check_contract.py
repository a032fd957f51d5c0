#!/usr/bin/env python3
"""check_contract.py HQVIEW SOURCE_DIR WORK_DIR [--expect-drift [--reuse]]

docs/contract.md against real outputs: runs `hqview analyze` on the bundled
examples (with --reference, --compare and a gate, so that every stage
writes its keys) and `hqview batch` on a two-row manifest, then checks that
every report.json / index.json key and every CSV column of the outputs is
documented in docs/contract.md, and that every documented one exists.
Exit 0 when both hold, 1 with the differences listed otherwise.

--expect-drift checks the check: it runs on a copy of the contract with one
documented key removed (`mesh.num_hexes`) and one invented
(`mesh.num_unicorns`), and exits 0 only when exactly those two are named.
With --reuse it reads the outputs already in WORK_DIR (docs.contract's,
its CTest fixture) instead of running hqview again: the drift is in the
contract, not in the outputs."""
import csv
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import contract_keys  # noqa: E402


def documented(contract, heading):
    """The backticked first cells of the tables under `heading` (a line
    starting with the heading text), up to the next heading of the same
    or a higher level."""
    lines = contract.split("\n")
    level = None
    keys = set()
    inside = False
    for line in lines:
        m = re.match(r"^(#+) (.*)", line)
        if m:
            if inside and len(m.group(1)) <= level:
                break
            if m.group(2).startswith(heading):
                inside, level = True, len(m.group(1))
            continue
        if inside:
            cell = re.match(r"^\| `([^`]+)` \|", line)
            if cell:
                keys.add(cell.group(1))
    return keys


def run(cmd, cwd):
    done = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    if done.returncode not in (0, 1):
        sys.exit(f"{' '.join(cmd)}: exit {done.returncode}\n{done.stderr}")


PROBLEMS = []


def compare(what, found, listed, nulls=frozenset()):
    """nulls: paths that are null in the outputs; the keys documented below
    them (an object that only some runs fill) need not appear."""
    missing = sorted(found - listed)
    stale = sorted(k for k in listed - found if not any(k.startswith(n + ".") for n in nulls))
    for k in missing:
        PROBLEMS.append(f"{what}: `{k}` is in the outputs but not in docs/contract.md")
    for k in stale:
        PROBLEMS.append(f"{what}: `{k}` is in docs/contract.md but not in the outputs")
    return not missing and not stale


def make_outputs(hqview, source, work):
    """Runs hqview so that every key and column appears: the outputs in work."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    examples = os.path.join(source, "examples")
    bundle = os.path.join(work, "bundle")
    run([hqview, "analyze", os.path.join(examples, "ball.mesh"), "--reference", os.path.join(examples, "ball.off"),
         "--compare", os.path.join(examples, "twisted_bar.mesh"), "--gate", "mesh.num_hexes>0", "--gate", "quality.by_kind.pyramid.metrics.scaled_jacobian.min>=0.2", "--simulate", "--size", "160x120",
         "--data", "csv,vtu.zlib", "-o", bundle, "-q"], work)
    # Both examples hold inverted hexes (the Poisson check is skipped there): a
    # 4 x 4 x 4 box with one moved vertex fills every key of `fem`.
    with open(os.path.join(work, "box.mesh"), "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n125\n")
        for k in range(5):
            for j in range(5):
                for i in range(5):
                    f.write(f"{i + (0.2 if (i, j, k) == (2, 2, 2) else 0)} {j} {k} 0\n")
        f.write("Hexahedra\n64\n")
        for k in range(4):
            for j in range(4):
                for i in range(4):
                    c = 1 + i + 5 * j + 25 * k
                    f.write(f"{c} {c + 1} {c + 6} {c + 5} {c + 25} {c + 26} {c + 31} {c + 30} 0\n")
        f.write("End\n")
    run([hqview, "analyze", "box.mesh", "--simulate", "--no-render", "--data", "csv", "-o", "box", "-q"], work)
    # A surface mesh's `structure` (its quad structure, other keys than a
    # hex mesh's): a regular 4 x 4 quad grid.
    with open(os.path.join(work, "quads.obj"), "w") as f:
        for j in range(5):
            for i in range(5):
                f.write(f"v {i} {j} 0\n")
        for j in range(4):
            for i in range(4):
                c = 1 + i + 5 * j
                f.write(f"f {c} {c + 1} {c + 6} {c + 5}\n")
    # ... measured against a planar outline (boundary_error.planar's keys).
    with open(os.path.join(work, "outline.obj"), "w") as f:
        f.write("v -0.5 -0.5 0\nv 4.5 -0.5 0\nv 4.5 4.5 0\nv -0.5 4.5 0\nf 1 2 3\nf 1 3 4\n")
    run([hqview, "analyze", "quads.obj", "--reference", "outline.obj", "--no-render", "-o", "quads", "-q"], work)
    with open(os.path.join(work, "manifest.csv"), "w") as f:
        f.write("mesh,label,model\n")
        f.write(os.path.join(examples, "ball.mesh") + ",m1,ball\n")
        f.write(os.path.join(examples, "twisted_bar.mesh") + ",m2,bar\n")
        f.write(os.path.join(work, "quads.obj") + ",m2,quads\n")  # meshes[].surface
    run([hqview, "batch", "manifest.csv", "-o", "batch", "--no-render", "-q"], work)
    # index.json's finite-element keys (meshes[].metrics, fem_correlation) exist with --simulate only.
    with open(os.path.join(work, "manifest_simulate.csv"), "w") as f:
        f.write("mesh,label,model\nbox.mesh,m3,box\n")
    run([hqview, "batch", "manifest_simulate.csv", "-o", "batch_simulate", "--no-render", "--simulate", "-q"], work)


def main():
    hqview, source, work = sys.argv[1], sys.argv[2], sys.argv[3]
    expect_drift = "--expect-drift" in sys.argv[4:]
    if not (expect_drift and "--reuse" in sys.argv[4:]):
        make_outputs(hqview, source, work)
    bundle = os.path.join(work, "bundle")
    with open(os.path.join(source, "docs", "contract.md"), encoding="utf-8") as f:
        contract = f.read()
    if expect_drift:
        row = "| `mesh.num_hexes` | int | hexahedra read |\n"
        if row not in contract:
            sys.exit("--expect-drift: the row it removes is gone from docs/contract.md")
        contract = contract.replace(row, "| `mesh.num_unicorns` | int | invented |\n")
    report = contract_keys.load(os.path.join(bundle, "report.json"))
    report["fem"] = contract_keys.load(os.path.join(work, "box", "report.json"))["fem"]
    quads = contract_keys.load(os.path.join(work, "quads", "report.json"))
    report["structure"].update(quads["structure"])
    # A surface mesh's overlap keys (issue 47 part E: the quad split, the self-intersecting faces).
    report["overlap"].update({k: v for k, v in quads["overlap"].items() if k not in report["overlap"]})
    ok = True
    stray = contract_keys.compare_mirrors(report)
    for k in sorted(stray):
        PROBLEMS.append(f"report.json: `{k}` has no counterpart outside compare")
    ok = not stray
    ok &= compare("report.json", contract_keys.report_keys(report) | contract_keys.stats_keys(report),
                  documented(contract, "report.json keys"), contract_keys.null_paths(report))
    ok &= compare("index.json", contract_keys.index_keys(contract_keys.load(os.path.join(work, "batch", "index.json")))
                  | contract_keys.index_keys(contract_keys.load(os.path.join(work, "batch_simulate", "index.json"))),
                  documented(contract, "index.json keys"))
    for name in ("cells.csv", "vertices.csv", "edges.csv"):
        with open(os.path.join(bundle, "data", name), newline="") as f:
            header = next(csv.reader(f))
        ok &= compare("data/" + name, set(header), documented(contract, "data/" + name))
    print("\n".join(PROBLEMS))
    if expect_drift:
        wanted = ["report.json: `mesh.num_hexes` is in the outputs but not in docs/contract.md",
                  "report.json: `mesh.num_unicorns` is in docs/contract.md but not in the outputs"]
        if PROBLEMS == wanted:
            print("the check names the removed and the invented key")
            return 0
        print("--expect-drift: expected exactly:\n" + "\n".join(wanted))
        return 1
    if ok:
        print("docs/contract.md lists exactly the keys and columns of the outputs")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
