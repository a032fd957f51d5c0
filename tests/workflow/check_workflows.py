#!/usr/bin/python3
"""The workflow recipes run as users run them (issue 21; docs/collections.md):

- workflow/Snakefile with Snakemake (Debian's 7.21): `-n` plans one analyze job
  per mesh plus the index; `--cores 2` gives outputs byte-identical to
  `hqview batch`; changing one mesh reruns its job and the index only; the
  Slurm profile's dry run plans the same jobs.
- examples/ci-workflow.yml: parsed, and its jobs' steps run in order on this
  machine (the matrix's shards, artifacts as folders, the merge, the diff
  against a baseline and the job summary); the merged index equals the
  unsharded batch's.

usage: check_workflows.py HQVIEW SOURCE_DIR SHARED_DATA WORKDIR
Exit 77 when Snakemake or the shared data is missing.
"""
import filecmp
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

FAILURES = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        FAILURES.append(what)


def tree_differences(a, b, ignore=("timings.json", ".jobs", ".snakemake")):
    out = []
    cmp = filecmp.dircmp(a, b, ignore=list(ignore))
    stack = [(cmp, "")]
    while stack:
        c, prefix = stack.pop()
        out += [prefix + n for n in c.left_only + c.right_only + c.funny_files]
        _, mismatch, errors = filecmp.cmpfiles(c.left, c.right, c.common_files, shallow=False)
        out += [prefix + n for n in mismatch + errors]
        stack += [(sub, prefix + name + "/") for name, sub in c.subdirs.items()]
    return sorted(out)


def jobs_planned(output):
    counts = {}
    for line in output.splitlines():
        m = re.match(r"^(\w+)\s+(\d+)\s+\d+\s+\d+\s*$", line)
        if m and m.group(1) != "total":
            counts[m.group(1)] = int(m.group(2))
    return counts


def snakemake_checks(hq, source, data, work):
    coll = work / "collection"
    shutil.rmtree(coll, ignore_errors=True)
    for rel in ["gao2016_sweeping/bunny_1.mesh", "gao2016_sweeping/hand7_1.mesh", "li2012_srf/fandisk.mesh",
                "smf2019/hex_cube_coarse.vtk"]:
        (coll / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(data / rel, coll / rel)
    # A mesh that cannot be read: a failed row, recorded the same way.
    (coll / "broken").mkdir()
    (coll / "broken" / "truncated.mesh").write_text("MeshVersionFormatted 2\nDimension 3\nVertices\n8\n0 0 0 0\n")
    n = 5
    out = work / "snake_out"
    ref = work / "batch_out"
    for d in (out, ref):
        shutil.rmtree(d, ignore_errors=True)
    options = "--no-render --gate quality.scaled_jacobian.min>=0.3"
    base = ["snakemake", "-s", str(source / "workflow" / "Snakefile"), "--directory", str(work),
            "--config", f"inputs={coll}", f"output={out}", f"hqview={hq}", f"options={options}"]
    plan = subprocess.run(base + ["-n", "--cores", "2"], capture_output=True, text=True)
    jobs = jobs_planned(plan.stdout + plan.stderr)
    check(plan.returncode == 0 and jobs.get("analyze") == n and jobs.get("index") == 1,
          f"snakemake -n: one analyze job per mesh and one index job ({jobs})")
    r = subprocess.run(base + ["--cores", "2", "-q"], capture_output=True, text=True)
    check(r.returncode == 0, f"snakemake --cores 2 ran (exit {r.returncode}) {r.stderr[-400:] if r.returncode else ''}")
    b = subprocess.run([hq, "batch", str(coll), "-o", str(ref), "-j", "2", "--quiet"] + options.split())
    differ = tree_differences(out, ref)
    check(b.returncode == 3 and not differ,
          f"snakemake's output is byte-identical to hqview batch's (batch exit {b.returncode}; differ: {differ[:5]})")
    # One mesh changes (Snakemake 7.21 compares small inputs' checksums, so
    # the content changes, not only the time): its job and the index rerun.
    changed = coll / "li2012_srf" / "fandisk.mesh"
    changed.chmod(0o644)
    with open(changed, "a") as f:
        f.write("\n")
    plan = subprocess.run(base + ["-n", "--cores", "2"], capture_output=True, text=True)
    jobs = jobs_planned(plan.stdout + plan.stderr)
    check(jobs.get("analyze") == 1 and jobs.get("index") == 1, f"one mesh changed: its job and the index rerun ({jobs})")
    subprocess.run(base + ["--cores", "2", "-q"], capture_output=True, text=True)
    shutil.rmtree(ref)
    subprocess.run([hq, "batch", str(coll), "-o", str(ref), "-j", "2", "--quiet"] + options.split())
    differ = tree_differences(out, ref)
    check(not differ, f"after the rerun, still byte-identical to a fresh batch (differ: {differ[:5]})")
    # The Slurm profile, as far as one machine allows: a dry run that plans
    # the same jobs with the profile's resources.
    slurm_out = work / "slurm_out"
    shutil.rmtree(slurm_out, ignore_errors=True)
    plan = subprocess.run(["snakemake", "-s", str(source / "workflow" / "Snakefile"), "--directory", str(work),
                           "--profile", str(source / "workflow" / "profiles" / "slurm"), "-n",
                           "--config", f"inputs={coll}", f"output={slurm_out}", f"hqview={hq}", f"options={options}"],
                          capture_output=True, text=True)
    text = plan.stdout + plan.stderr
    jobs = jobs_planned(text)
    check(plan.returncode == 0 and jobs.get("analyze") == n and "slurm_partition=normal" in text and "mem_mb=4000" in text,
          f"Slurm profile dry run: {jobs}, resources from the profile" + ("" if plan.returncode == 0 else text[-400:]))


def manifest_up_checks(hq, source, data, work):
    """A manifest with an up axis per mesh (issue 45): each bundle's cameras
    use its row's axis (the run's --up for a row without one), and the
    Snakefile's jobs equal batch byte for byte."""
    coll = work / "up_collection"
    shutil.rmtree(coll, ignore_errors=True)
    coll.mkdir(parents=True)
    rows = [("kitten_1.mesh", "gao2016_sweeping/kitten_1.mesh", "+y"),
            ("fandisk.mesh", "li2012_srf/fandisk.mesh", ""),
            ("hex_cube_coarse.vtk", "smf2019/hex_cube_coarse.vtk", "-x")]
    for name, rel, _ in rows:
        shutil.copy(data / rel, coll / name)
    (coll / "meshes.csv").write_text("mesh,up\n" + "".join(f"{name},{up}\n" for name, _, up in rows))
    out, ref = work / "up_snake_out", work / "up_batch_out"
    for d in (out, ref):
        shutil.rmtree(d, ignore_errors=True)
    options = "--up +z --views overview --size 200x150 --no-viewer --data none"
    r = subprocess.run(["snakemake", "-s", str(source / "workflow" / "Snakefile"), "--directory", str(work), "--cores",
                        "2", "-q", "--config", f"inputs={coll / 'meshes.csv'}", f"output={out}", f"hqview={hq}",
                        f"options={options}"], capture_output=True, text=True)
    check(r.returncode == 0, f"snakemake with an up column ran (exit {r.returncode}) {r.stderr[-400:] if r.returncode else ''}")
    subprocess.run([hq, "batch", str(coll / "meshes.csv"), "-o", str(ref), "-j", "2", "--quiet"] + options.split())
    differ = tree_differences(out, ref)
    check(not differ, f"with an up column, snakemake's output is byte-identical to batch's (differ: {differ[:5]})")
    expected = {"+y": [0, 1, 0], "": [0, 0, 1], "-x": [-1, 0, 0]}
    for name, _, up in rows:
        report = json.loads((ref / name / "report.json").read_text())
        ups = [c["up"] for v in report["views"] for c in v["cameras"] if c]
        # A camera's up is the axis made orthogonal to its view direction:
        # within 35 degrees of it (the views look from 15-35 degrees above).
        near = [sum(a * b for a, b in zip(u, expected[up])) > 0.8 for u in ups]
        check(bool(ups) and all(near), f"{name}: every camera's up is near the row's axis {up or '(the run: +z)'} ({ups[:2]})")


def github_actions_matrix(hq, source, data, work):
    """Runs examples/ci-workflow.yml's jobs in order, as a runner would on one machine."""
    import yaml
    wf = yaml.safe_load((source / "examples" / "ci-workflow.yml").read_text())
    root = work / "gha"
    shutil.rmtree(root, ignore_errors=True)
    meshes = root / "data" / "meshes"
    for rel in ["gao2016_sweeping/bunny_1.mesh", "gao2016_sweeping/hand7_1.mesh", "li2012_srf/fandisk.mesh",
                "smf2019/hex_cube_coarse.vtk", "livesu2016_skeleton/armadillo.mesh"]:
        (meshes / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(data / rel, meshes / rel)
    artifacts = root / "artifacts"
    env_base = dict(os.environ, PATH=str(Path(hq).parent) + os.pathsep + os.environ["PATH"])
    env_base.update({k: str(v) for k, v in wf.get("env", {}).items()})
    order = []
    for job_name in ["analyse", "merge-and-compare"]:
        job = wf["jobs"][job_name]
        matrix = job.get("strategy", {}).get("matrix", {})
        combos = [{"shard": s} for s in matrix["shard"]] if "shard" in matrix else [{}]
        for combo in combos:
            wd = root / ("run-" + job_name + "-" + "-".join(str(v) for v in combo.values()))
            shutil.rmtree(wd, ignore_errors=True)
            wd.mkdir()
            (wd / "data").symlink_to(root / "data")
            summary = wd / "summary.txt"
            for step in job["steps"]:
                name = step.get("name", step.get("uses", ""))
                ctx = {"matrix.shard": str(combo.get("shard", "")), "github.event_name": "pull_request"}
                cond = step.get("if")
                if cond:
                    cond_text = re.sub(r"\$\{\{\s*|\s*\}\}", "", cond)
                    m = re.match(r"(github\.event_name)\s*(==|!=)\s*'([^']*)'", cond_text)
                    if m and ((ctx[m.group(1)] == m.group(3)) != (m.group(2) == "==")):
                        continue
                uses = step.get("uses", "")
                with_ = {k: re.sub(r"\$\{\{\s*matrix\.shard\s*\}\}", ctx["matrix.shard"], str(v))
                         for k, v in step.get("with", {}).items()}
                if uses.startswith("actions/checkout"):
                    continue
                if uses.startswith("actions/upload-artifact"):
                    dest = artifacts / with_["name"]
                    shutil.rmtree(dest, ignore_errors=True)
                    shutil.copytree(wd / with_["path"], dest)
                    order.append(f"{job_name}{combo}: upload {with_['name']}")
                    continue
                if uses.startswith("actions/download-artifact"):
                    pattern = with_["pattern"].replace("*", ".*")
                    for a in sorted(artifacts.iterdir()):
                        if re.fullmatch(pattern, a.name):
                            shutil.copytree(a, wd / with_["path"] / a.name)
                    order.append(f"{job_name}{combo}: download {with_['pattern']}")
                    continue
                if uses.startswith("dawidd6/action-download-artifact"):
                    # The baseline: last night's report, here the same collection analysed once.
                    baseline = wd / with_["path"]
                    subprocess.run([hq, "batch", str(meshes), "-o", str(baseline), "--no-render", "--quiet"])
                    order.append(f"{job_name}{combo}: baseline")
                    continue
                if name == "Install HQView":
                    continue  # hqview is on PATH already (the build under test)
                script = step["run"]
                script = re.sub(r"\$\{\{\s*matrix\.shard\s*\}\}", ctx["matrix.shard"], script)
                shell = step.get("shell", "bash -e {0}").replace("{0}", "").split()
                env = dict(env_base, GITHUB_STEP_SUMMARY=str(summary))
                r = subprocess.run(shell + ["-c", script], cwd=wd, env=env, capture_output=True, text=True)
                order.append(f"{job_name}{combo}: {name} (exit {r.returncode})")
                check(r.returncode == 0, f"GitHub Actions {job_name} {combo} step '{name}': exit {r.returncode}"
                      + (" " + r.stderr[-300:] if r.returncode else ""))
        if job_name == "analyse":
            check(len([a for a in artifacts.iterdir() if a.name.startswith("shard-")]) == len(combos),
                  f"the matrix's {len(combos)} shards each uploaded their output")
    report = root / "run-merge-and-compare-" / "report"
    ref = root / "unsharded"
    subprocess.run([hq, "batch", str(meshes), "-o", str(ref), "--no-render", "--quiet"])
    same = all((report / f).is_file() and (report / f).read_bytes() == (ref / f).read_bytes()
               for f in ["index.json", "index.html", "summary.md"])
    check(same, "the merged shards' index.json, index.html and summary.md equal the unsharded batch's")
    summary = (root / "run-merge-and-compare-" / "summary.txt")
    check(summary.is_file() and "quality.scaled_jacobian.min" in summary.read_text(),
          "the diff against the baseline went into the job summary")
    print("      steps in order: " + "; ".join(order), flush=True)


def main():
    hq, source, data, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3]) / "meshes", Path(sys.argv[4])
    hq = str(Path(hq).resolve())
    if shutil.which("snakemake") is None or not data.is_dir():
        print("skip: snakemake or the shared data is missing")
        return 77
    work = work.resolve()
    work.mkdir(parents=True, exist_ok=True)
    snakemake_checks(hq, source.resolve(), data.resolve(), work)
    manifest_up_checks(hq, source.resolve(), data.resolve(), work)
    github_actions_matrix(hq, source.resolve(), data.resolve(), work)
    print(f"{len(FAILURES)} failed" if FAILURES else "all workflow checks passed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
