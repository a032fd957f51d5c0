#!/usr/bin/python3
"""The CI integrations as a runner would run them (issue 49; README "In CI"):

- action.yml validated by @action-validator/cli (tests/ci/package-lock.json),
  and held to its rules: a composite action whose every `run:` is one script
  of action/ through $GITHUB_ACTION_PATH, with its `shell:`, and no `${{ }}`
  in a `run:` (inputs reach the scripts through `env:`).
- The action's steps run in order with a fake GitHub environment (GITHUB_*
  files, a pull_request event, RUNNER_TEMP) and a fake `gh` on PATH that
  records its calls (tests/ci/fake_gh.py); `uses:` steps are simulated
  (actions/cache skipped, upload-artifact copies and gives a URL). Checked:
  the outputs, the job summary, the comment (marker, links, size), the
  calls, the last step's exit code, for a passing gate, a failing gate,
  a diff with a regression, a batch of 200 meshes, comment=update twice (one
  comment), comment=new, a push event, and a fork's read-only token.
- ci/hqview.gitlab-ci.yml's script lines run in one bash, in order, as
  GitLab's shell and docker executors run them (its before_script installs
  packages and is not run here): junit.xml, metrics.txt, the exit code.

usage: check_ci.py HQVIEW SOURCE_DIR SHARED_DATA WORKDIR
Exit 77 when the shared data is missing.
"""
import json
import os
import random
import re
import shutil
import subprocess
import sys
from pathlib import Path

import yaml

FAILURES = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        FAILURES.append(what)


def grid_mesh(path, n, jitter, seed, fold=False):
    """An n^3-hex MEDIT grid of unit cells, vertices moved by up to `jitter`
    (a seeded uniform draw); `fold` pushes one interior vertex through a face
    of its hexes (inverted hexes)."""
    rng = random.Random(seed)
    m = n + 1
    verts = []
    for k in range(m):
        for j in range(m):
            for i in range(m):
                inner = 0 < i < n and 0 < j < n and 0 < k < n
                d = [rng.uniform(-jitter, jitter) if inner else 0.0 for _ in range(3)]
                verts.append([i + d[0], j + d[1], k + d[2]])
    if fold:
        verts[1 + m * (1 + m * 1)][2] += 1.6

    def v(i, j, k):
        return 1 + i + m * (j + m * k)

    hexes = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                hexes.append([v(i, j, k), v(i + 1, j, k), v(i + 1, j + 1, k), v(i, j + 1, k),
                              v(i, j, k + 1), v(i + 1, j, k + 1), v(i + 1, j + 1, k + 1), v(i, j + 1, k + 1)])
    lines = ["MeshVersionFormatted 2", "Dimension 3", "Vertices", str(len(verts))]
    lines += [f"{x:.9g} {y:.9g} {z:.9g} 0" for x, y, z in verts]
    lines += ["Hexahedra", str(len(hexes))] + [" ".join(map(str, h)) + " 0" for h in hexes] + ["End"]
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text("\n".join(lines) + "\n")


def action_rules(source):
    action = yaml.safe_load((source / "action.yml").read_text())
    validator = source / "tests" / "ci" / "node_modules" / ".bin" / "action-validator"
    if validator.exists():
        r = subprocess.run([str(validator), str(source / "action.yml")], capture_output=True, text=True)
        check(r.returncode == 0, f"action-validator accepts action.yml (exit {r.returncode}) {r.stdout[-600:]}")
    else:
        check(False, "action-validator is installed (cd tests/ci && npm ci)")
    check(action["runs"]["using"] == "composite", "action.yml is a composite action")
    if shutil.which("shellcheck"):
        r = subprocess.run(["shellcheck", "-x", *sorted(str(p) for p in (source / "action").glob("*.sh"))],
                           capture_output=True, text=True)
        check(r.returncode == 0, f"shellcheck passes action/*.sh {r.stdout[-800:]}")
    else:
        check(False, "shellcheck is installed (scripts/setup)")
    for step in action["runs"]["steps"]:
        if "run" not in step:
            continue
        run = step["run"].strip()
        ok = (step.get("shell") == "bash" and "${{" not in run and
              re.fullmatch(r'"\$GITHUB_ACTION_PATH/action/[a-z_]+\.sh"', run) is not None and
              (source / run.strip('"').replace("$GITHUB_ACTION_PATH/", "")).is_file())
        check(ok, f"step '{step['name']}': one script of action/, shell bash, no expression in run ({run})")
    return action


class Runner:
    """One run of the action's steps, as GitHub's runner would run them."""

    def __init__(self, source, action, work, hq_dir, fake_gh_dir, event="pull_request"):
        self.source, self.action, self.work = source, action, work
        shutil.rmtree(work, ignore_errors=True)
        (work / "temp").mkdir(parents=True)
        self.summary = work / "summary.md"
        self.outputs_file = work / "outputs"
        self.event = work / "event.json"
        self.event.write_text(json.dumps({"pull_request": {"number": 7}} if event == "pull_request"
                                         else {"ref": "refs/heads/main"}))
        self.env = dict(os.environ, PATH=f"{fake_gh_dir}{os.pathsep}{hq_dir}{os.pathsep}{os.environ['PATH']}",
                        GITHUB_ACTION_PATH=str(source), GITHUB_STEP_SUMMARY=str(self.summary),
                        GITHUB_EVENT_PATH=str(self.event), GITHUB_EVENT_NAME=event, GITHUB_REPOSITORY="owner/repo",
                        RUNNER_TEMP=str(work / "temp"), GITHUB_WORKSPACE=str(work))
        self.artifacts = work / "artifacts"

    def expand(self, text, inputs, steps):
        def value(expr):
            expr = expr.strip()
            if expr.startswith("inputs."):
                name = expr[len("inputs."):]
                default = self.action["inputs"][name].get("default", "")
                return str(inputs.get(name, default))
            if m := re.fullmatch(r"steps\.([\w-]+)\.outputs\.([\w-]+)", expr):
                return steps.get(m.group(1), {}).get(m.group(2), "")
            if expr == "runner.temp":
                return str(self.work / "temp")
            if expr == "github.token":
                return "fake-token"
            if expr in ("runner.os", "github.action_ref", "github.action_repository"):
                return "x"
            raise ValueError("unknown expression " + expr)
        return re.sub(r"\$\{\{(.*?)\}\}", lambda m: value(m.group(1)), str(text))

    def condition(self, cond, inputs, steps):
        m = re.fullmatch(r"\s*([\w.-]+)\s*(==|!=)\s*''\s*", cond)
        assert m, "condition not understood: " + cond
        v = self.expand("${{ " + m.group(1) + " }}", inputs, steps)
        return (v == "") == (m.group(2) == "==")

    def run(self, inputs, gh_mode=""):
        """Every step; returns (step outputs, exit codes by step name, action outputs)."""
        steps, codes = {}, {}
        self.env["FAKE_GH_MODE"] = gh_mode
        for step in self.action["runs"]["steps"]:
            name = step["name"]
            if "if" in step and not self.condition(step["if"], inputs, steps):
                continue
            uses = step.get("uses", "")
            if uses.startswith("actions/cache"):
                continue
            if uses.startswith("actions/upload-artifact"):
                with_ = {k: self.expand(v, inputs, steps) for k, v in step["with"].items()}
                src = self.work / with_["path"]
                self.artifacts.mkdir(exist_ok=True)
                n = len(list(self.artifacts.iterdir())) + 1
                dest = self.artifacts / str(n)
                (shutil.copytree if src.is_dir() else lambda a, b: (b.mkdir(), shutil.copy(a, b)))(src, dest)
                steps[step["id"]] = {"artifact-url": f"https://github.com/owner/repo/actions/runs/1/artifacts/{n}",
                                     "archive": str(with_.get("archive", "true")).lower()}
                continue
            if name == "Install HQView":
                continue  # the build under test is on PATH (install.sh is checked on its own)
            env = dict(self.env)
            env.update({k: self.expand(v, inputs, steps) for k, v in step.get("env", {}).items()})
            out = self.work / "temp" / "step-output"
            out.write_text("")
            env["GITHUB_OUTPUT"] = str(out)
            script = self.expand(step["run"], inputs, steps)
            r = subprocess.run(["bash", "-e", "-c", script], cwd=self.work, env=env, capture_output=True, text=True)
            codes[name] = r.returncode
            self.log = getattr(self, "log", "") + r.stdout + r.stderr
            parsed, text = {}, out.read_text()
            for m in re.finditer(r"^([\w-]+)<<(\S+)\n(.*?)\n\2$", text, re.S | re.M):
                parsed[m.group(1)] = m.group(3)
            if "id" in step:
                steps[step["id"]] = parsed
        outputs = {k: self.expand(v["value"], inputs, steps) for k, v in self.action["outputs"].items()}
        return steps, codes, outputs


def calls(log):
    return [json.loads(line) for line in log.read_text().splitlines()] if log.exists() else []


def action_runs(hq, source, data, work, action):
    hq_dir = str(Path(hq).parent)
    fake = work / "fakebin"
    fake.mkdir(parents=True, exist_ok=True)
    (fake / "gh").unlink(missing_ok=True)
    (fake / "gh").symlink_to(source / "tests" / "ci" / "fake_gh.py")
    gh_log, gh_state = work / "gh.log", work / "gh.json"
    os.environ.update(FAKE_GH_LOG=str(gh_log), FAKE_GH_STATE=str(gh_state))
    for f in (gh_log, gh_state):
        f.unlink(missing_ok=True)
    mesh = data / "smf2019" / "hex_cube_coarse.vtk"

    # 1. A passing gate, comment=update: one POST, then one PATCH of the same comment.
    run = Runner(source, action, work / "pass", hq_dir, fake)
    shutil.copy(mesh, run.work / "cube.vtk")
    inputs = {"inputs": "cube.vtk", "options": "--no-render --views main", "gates": "quality.num_inverted==0\n"}
    steps, codes, outputs = run.run(inputs)
    report = json.loads((run.work / "hqview-report" / "report.json").read_text())
    check(outputs["exit-code"] == "0" and outputs["gate-status"] == "passed" and outputs["bundle"] == "hqview-report"
          and outputs["worst-mesh"] == "cube.vtk" and outputs["artifact-url"].endswith("/artifacts/1"),
          f"passing gate: outputs {outputs}")
    check(outputs["report-url"].endswith("/artifacts/2") and steps["upload-report"]["archive"] == "false"
          and (run.artifacts / "2" / "report.html").is_file(),
          "passing gate: report.html uploaded as a file of its own (archive: false)")
    check(report["quality"]["num_inverted"] == 0, "passing gate: the mesh has no inverted hex (the gate's truth)")
    check(codes.get("Gate") == 0 and all(c == 0 for c in codes.values()), f"passing gate: every step exit 0 {codes}")
    c = calls(gh_log)
    check([x["args"][:3] for x in c] == [["api", "--paginate", "repos/owner/repo/issues/7/comments"],
                                          ["api", "-X", "POST"]], f"passing gate: gh listed then posted ({c})")
    body = c[-1]["input"]["body"] if c else ""
    summary_md = (run.work / "hqview-report" / "summary.md").read_text()
    check(body.startswith("<!-- hqview-action:hqview -->\n") and "Mesh Quality" in body or "hex_cube" in body or
          summary_md.splitlines()[0] in body, "passing gate: the comment has the marker and the bundle's summary")
    rel = re.findall(r"\]\((?!<?https?:|#)([^)]*)\)", body)
    check(not rel and "(<https://github.com/owner/repo/actions/runs/1/artifacts/2>)" in body,
          f"passing gate: no relative link left in the comment, links point at report.html's artifact ({rel[:3]})")
    check(run.summary.read_text().strip() == body.strip(), "passing gate: the job summary is the comment")
    steps, codes, outputs = run.run(inputs)
    c = calls(gh_log)
    comments = json.loads(gh_state.read_text())
    check(len(comments) == 1 and c[-1]["args"][:4] == ["api", "-X", "PATCH", f"repos/owner/repo/issues/comments/{comments[0]['id']}"],
          f"comment=update on a second run: the same comment edited ({len(comments)} comments)")
    run.run(dict(inputs, comment="new"))
    check(len(json.loads(gh_state.read_text())) == 2, "comment=new: a second comment")
    n = len(calls(gh_log))
    run.run(dict(inputs, comment="off"))
    check(len(calls(gh_log)) == n, "comment=off: gh not called")
    push = Runner(source, action, work / "push", hq_dir, fake, event="push")
    shutil.copy(mesh, push.work / "cube.vtk")
    _, codes, outputs = push.run(inputs)
    check(len(calls(gh_log)) == n and codes.get("Gate") == 0 and push.summary.read_text().startswith("<!-- hqview"),
          "a push event: no comment, the summary written")

    # 2. A failing gate: outputs still written, only the last step fails; fail-on-gate false keeps it green.
    steps, codes, outputs = run.run(dict(inputs, gates="quality.scaled_jacobian.min>=0.999"))
    check(outputs["exit-code"] == "1" and outputs["gate-status"] == "failed" and outputs["bundle"] == "hqview-report",
          f"failing gate: outputs {outputs}")
    check(codes.get("Gate") == 1 and all(c == 0 for k, c in codes.items() if k != "Gate"),
          f"failing gate: only the last step fails {codes}")
    check("| quality\\.scaled\\_jacobian\\.min&gt;\\=0\\.999 | 0.675397 | **fail** |" in
          run.summary.read_text().split("<!-- hqview-action")[-1],
          "failing gate: the summary names the failed rule")
    _, codes, _ = run.run(dict(inputs, gates="quality.scaled_jacobian.min>=0.999", **{"fail-on-gate": "false"}))
    check(codes.get("Gate") == 0, "failing gate with fail-on-gate false: the job stays green")
    _, codes, outputs = run.run(dict(inputs, inputs="missing.vtk"))
    check(outputs["gate-status"] == "error" and outputs["exit-code"] == "3" and codes.get("Gate") == 1,
          f"an unreadable mesh: gate-status error, exit code 3, the last step fails ({outputs['exit-code']})")
    _, codes, outputs = run.run(dict(inputs, options="--no-render 'unbalanced"))
    check(outputs["gate-status"] == "error" and codes.get("Gate") == 1 and codes.get("Analyse") == 0,
          "options with an unbalanced quote: an error, reported by the last step")

    # 3. A fork's read-only token: the comment falls back to the summary, nothing fails.
    run.summary.write_text("")
    _, codes, outputs = run.run(inputs, gh_mode="readonly")
    check(all(c == 0 for c in codes.values()) and "read-only" in run.summary.read_text(),
          f"read-only token: no step fails, the summary says why there is no comment {codes}")

    # 4. A batch of 200 meshes against a baseline with regressions: the diff's
    # gate fails, the comment holds the regressions and stays under the cap.
    run = Runner(source, action, work / "batch", hq_dir, fake)
    for i in range(200):
        grid_mesh(run.work / "base" / f"m{i:03d}.mesh", 2, 0.05, i)
        # Every mesh moves a little; three get much worse (one folds: inverted hexes).
        grid_mesh(run.work / "meshes" / f"m{i:03d}.mesh", 2, 0.3 if i in (17, 101) else 0.06, i, fold=(i == 150))
    subprocess.run([hq, "batch", str(run.work / "base"), "-o", str(run.work / "baseline"), "--no-render", "-j", "2",
                    "--quiet"], check=True)
    gh_state.unlink(missing_ok=True)
    steps, codes, outputs = run.run({"inputs": "meshes", "options": "--no-render -j 2", "baseline": "baseline"})
    check(outputs["exit-code"] == "1" and outputs["gate-status"] == "failed" and outputs["worst-mesh"] == "m150.mesh"
          and codes.get("Gate") == 1, f"diff with a regression: outputs {outputs}, codes {codes}")
    comments = json.loads(gh_state.read_text()) if gh_state.exists() else []
    body = comments[0]["body"] if comments else ""
    diff = subprocess.run([hq, "diff", str(run.work / "baseline"), str(run.work / "hqview-report")],
                          capture_output=True, text=True).stdout
    rows = len(diff.splitlines())
    small = subprocess.run([hq, "diff", str(run.work / "baseline"), str(run.work / "hqview-report"), "--markdown",
                            str(run.work / "small.md"), "--markdown-max-chars", "999"], capture_output=True, text=True)
    check(small.returncode == 2 and not (run.work / "small.md").exists(), "diff --markdown-max-chars 999: exit 2")
    check(len(body) <= 65536 and body.startswith("<!-- hqview-action:hqview -->") and "<!-- hqview diff -->" in body,
          f"200 meshes: one comment of {len(body)} characters (<= 65,536) with both markers ({rows} changes in all)")
    check(re.search(r"_\d+ of \d+ rows left out to stay under 60000 characters", body) is not None,
          "200 meshes: the diff says how many rows were left out")
    kept = [line for line in body.splitlines() if line.startswith("| ❌")]
    check(len([line for line in kept if "m150\\.mesh" in line]) == 2,
          f"200 meshes: both failed gates of the folded mesh are kept ({[k for k in kept if 'm150' in k]})")
    check(all(f"| {m}\\.mesh | `quality.scaled_jacobian.min` |" in body for m in ("m017", "m101", "m150")),
          "200 meshes: the three largest drops of min SJ are kept")
    return True


def install_script(source, work):
    """action/install.sh's logic with stand-ins for apt-get, dpkg-query, curl,
    scripts/setup and scripts/build (installing for real would change this
    machine): the .deb path, URL and refusals, and the build from the
    action's checkout, each putting hqview's directory on GITHUB_PATH."""
    root = work / "install"
    shutil.rmtree(root, ignore_errors=True)
    (root / "action").mkdir(parents=True)
    shutil.copy(source / "action" / "install.sh", root / "action" / "install.sh")
    log = root / "calls.log"
    fake = root / "fakebin"
    fake.mkdir()
    stubs = {
        "apt-get": 'echo "apt-get $*" >> "$CALLS"; case "$*" in *install*) mkdir -p "$FAKE_PREFIX/bin";'
                   ' printf "#!/bin/sh\necho hqview 9.9\n" > "$FAKE_PREFIX/bin/hqview"; chmod +x "$FAKE_PREFIX/bin/hqview";; esac',
        "dpkg-query": "exit 1",
        "curl": 'echo "curl $*" >> "$CALLS"; while [ $# -gt 0 ]; do [ "$1" = --output ] && : > "$2"; shift; done',
        "jq": "exit 0", "gh": "exit 0",
    }
    for name, body in stubs.items():
        (fake / name).write_text("#!/bin/sh\n" + body + "\n")
        (fake / name).chmod(0o755)
    (root / "scripts").mkdir()
    (root / "scripts" / "setup").write_text('#!/bin/sh\necho "setup $*" >> "$CALLS"\n')
    (root / "scripts" / "build").write_text('#!/bin/sh\necho "build $HQVIEW_BUILD_DIR $*" >> "$CALLS"\n'
                                            'mkdir -p "$HQVIEW_BUILD_DIR/apps/hqview"\n'
                                            'printf "#!/bin/sh\\necho hqview built\\n" > "$HQVIEW_BUILD_DIR/apps/hqview/hqview"\n'
                                            'chmod +x "$HQVIEW_BUILD_DIR/apps/hqview/hqview"\n')
    for f in ("setup", "build"):
        (root / "scripts" / f).chmod(0o755)
    (root / "hqview_9.9_amd64.deb").write_bytes(b"!<arch>\n")

    def install(deb, cwd=root):
        log.write_text("")
        gp = root / "github_path"
        gp.write_text("")
        env = dict(os.environ, PATH=f"{fake}:/usr/bin:/bin", CALLS=str(log), FAKE_PREFIX=str(fake / "prefix"),
                   HQVIEW_DEB=deb, HQVIEW_BUILD_DIR=str(root / "build"), GITHUB_PATH=str(gp), RUNNER_TEMP=str(root))
        env["PATH"] = f"{fake / 'prefix' / 'bin'}:{env['PATH']}"
        r = subprocess.run(["bash", str(root / "action" / "install.sh")], cwd=cwd, env=env, capture_output=True, text=True)
        return r.returncode, log.read_text(), gp.read_text(), r.stdout + r.stderr

    code, calls_, path, out = install("hqview_9.9_amd64.deb")
    check(code == 0 and "install -y -q --no-install-recommends ./hqview_9.9_amd64.deb" in calls_
          and path.strip() == str(fake / "prefix" / "bin") and "hqview 9.9" in out,
          f"install.sh, a .deb path: apt-get installs ./FILE, hqview's directory on GITHUB_PATH ({calls_!r} {out[-200:]})")
    code, calls_, path, out = install("https://example.org/hqview_9.9_amd64.deb")
    check(code == 0 and f"--output {root}/hqview.deb -- https://example.org/hqview_9.9_amd64.deb" in calls_
          and f"install -y -q --no-install-recommends {root}/hqview.deb" in calls_,
          f"install.sh, an https URL: downloaded with curl, then installed ({calls_!r})")
    for deb, what in [("missing.deb", "no such file"), ("ftp://example.org/x.deb", "only a path or an https")]:
        code, calls_, path, out = install(deb)
        check(code == 2 and what in out and "install" not in calls_ and not path,
              f"install.sh refuses {deb}: exit {code}, '{what}', nothing installed")
    code, calls_, path, out = install("")
    check(code == 0 and "setup --build" in calls_ and f"build {root}/build -DHQVIEW_BUILD_TESTS=OFF" in calls_
          and path.strip() == str(root / "build" / "apps" / "hqview") and "hqview built" in out,
          f"install.sh without a .deb: scripts/setup --build and scripts/build from the action's checkout ({calls_!r})")


def gitlab_template(hq, source, data, work):
    tpl = yaml.safe_load((source / "ci" / "hqview.gitlab-ci.yml").read_text())[".hqview"]
    art = tpl["artifacts"]
    check(art["reports"]["junit"] == "hqview-report/junit.xml" and art["reports"]["metrics"] == "metrics.txt"
          and art.get("expose_as") and "hqview-report/" in art["paths"], "GitLab template: junit, metrics, expose_as")
    for case, gates, want in [("pass", "quality.num_inverted==0", 0), ("fail", "quality.scaled_jacobian.min>=0.999", 1)]:
        wd = work / ("gitlab-" + case)
        shutil.rmtree(wd, ignore_errors=True)
        for rel in ["smf2019/hex_cube_coarse.vtk", "li2012_srf/fandisk.mesh"]:
            (wd / "meshes" / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(data / rel, wd / "meshes" / rel)
        env = dict(os.environ, PATH=str(Path(hq).parent) + os.pathsep + os.environ["PATH"])
        env.update({k: str(v) for k, v in tpl["variables"].items()})
        env.update(HQVIEW_GATES=gates, HQVIEW_OPTIONS="--no-render")
        # GitLab: every line of `script` in one shell, stopping at the first failing line.
        script = "set -eo pipefail\n" + "\n".join(tpl["script"]) + "\n"
        r = subprocess.run(["bash", "-c", script], cwd=wd, env=env, capture_output=True, text=True)
        check(r.returncode == want, f"GitLab template, {case}: the job's exit code {r.returncode} (want {want}) {r.stderr[-300:]}")
        metrics = (wd / "metrics.txt").read_text() if (wd / "metrics.txt").exists() else ""
        index = json.loads((wd / "hqview-report" / "index.json").read_text())
        fandisk = [m for m in index["meshes"] if m["path"].endswith("fandisk.mesh")][0]
        line = f'hqview_min_scaled_jacobian{{mesh="{fandisk["path"]}"}} {fandisk["headline"]["quality.scaled_jacobian.min"]}'
        ok = metrics.endswith("# EOF\n") and line in metrics.splitlines() and 'hqview_meshes{status="ok"}' in metrics
        check(ok, f"GitLab template, {case}: metrics.txt in OpenMetrics with the index's values ({line})")
        junit = (wd / "hqview-report" / "junit.xml").read_text()
        check(("<failure" in junit) == (want == 1), f"GitLab template, {case}: junit.xml failures as the gates")
        check((wd / "hqview-report" / "report.html").is_file() == ("--single-file" in " ".join(tpl["script"])),
              f"GitLab template, {case}: the one-file report")


def main():
    hq, source, data, work = sys.argv[1], Path(sys.argv[2]).resolve(), Path(sys.argv[3]) / "meshes", Path(sys.argv[4])
    hq = str(Path(hq).resolve())
    if not data.is_dir():
        print("skip: the shared data is missing")
        return 77
    work = work.resolve()
    work.mkdir(parents=True, exist_ok=True)
    action = action_rules(source)
    action_runs(hq, source, data.resolve(), work, action)
    install_script(source, work)
    gitlab_template(hq, source, data.resolve(), work)
    print(f"{len(FAILURES)} failed" if FAILURES else "all CI checks passed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
