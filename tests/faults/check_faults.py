#!/usr/bin/env python3
"""Faults that must lose nothing (issue 21; docs/testing.md, "Faults").

usage: check_faults.py HQVIEW SHARED_DATA WORKDIR [--full] [--trials N] [--render] [--seed S]

Without --full (CI): a few SIGKILL trials at random moments and at each
deterministic fault point over four small meshes without rendering, then one
check of each other fault. --full: the whole shared collection, --trials
random kills (default 20), and --render to draw the views as well.

Each check prints one line; the exit code is 1 when one failed, 77 when the
machine lacks what every check needs.
"""
import argparse
import json
import os
import random
import resource
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

FAILURES = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        FAILURES.append(what)
    return ok


def run(cmd, env=None, limit_fsize=None, timeout=600):
    def limits():
        if limit_fsize is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit_fsize, limit_fsize))
    full_env = dict(os.environ, **(env or {}))
    return subprocess.run(cmd, env=full_env, capture_output=True, text=True, timeout=timeout, preexec_fn=limits)


def leftovers(root):
    """Temporary entries a run left anywhere under root."""
    found = []
    for dirpath, dirnames, filenames in os.walk(root):
        for name in dirnames + filenames:
            if ".hqview-tmp-" in name or ".hqview-old-" in name:
                found.append(os.path.join(dirpath, name))
    return found


def files_of(bundle):
    return sorted(str(p.relative_to(bundle)) for p in Path(bundle).rglob("*") if p.is_file())


def same_bytes(a, b):
    return Path(a).read_bytes() == Path(b).read_bytes()


def bundles_of(index_dir):
    index = json.loads((Path(index_dir) / "index.json").read_text())
    return [m["bundle"] for m in index["meshes"] if m.get("bundle")]


def complete_or_absent(out, ref, bundles):
    """Every bundle of the reference run is absent in out or has exactly its files
    (report.json byte-identical): never a partial bundle."""
    bad = []
    for b in bundles:
        d = Path(out) / b
        if not d.exists():
            continue
        if files_of(d) != files_of(Path(ref) / b) or not same_bytes(d / "report.json", Path(ref) / b / "report.json"):
            bad.append(b)
    return bad


def outputs_equal(out, ref, bundles):
    """index.json, index.html, summary.md, junit.xml and every report.json as in ref."""
    differ = [f for f in ["index.json", "index.html", "summary.md", "junit.xml"]
              if not same_bytes(Path(out) / f, Path(ref) / f)]
    differ += [b for b in bundles if not same_bytes(Path(out) / b / "report.json", Path(ref) / b / "report.json")]
    return differ


def kill_trials(hq, collection, work, args, rng):
    batch = [hq, "batch", str(collection), "-j", "2"] + ([] if args.render else ["--no-render"]) + ["--quiet"]
    ref = work / "kill_ref"
    start = time.monotonic()
    r = run(batch + ["-o", str(ref)])
    ref_seconds = time.monotonic() - start
    if not check(r.returncode in (0, 1, 3) and (ref / "index.json").exists(), f"reference batch run (exit {r.returncode}, {ref_seconds:.2f} s)"):
        return
    bundles = bundles_of(ref)
    trials = [("point", p) for p in ["bundle-before-swap", "bundle-before-swap@3", "batch-before-index", "batch-index-write"]]
    trials += [("random", rng.uniform(0.0, ref_seconds)) for _ in range(args.trials)]
    out = work / "kill_out"
    shutil.rmtree(out, ignore_errors=True)
    killed_before_end = 0
    for kind, what in trials:
        if rng.random() < 0.3:  # sometimes from nothing, else over what the last trial left
            shutil.rmtree(out, ignore_errors=True)
        if kind == "point":
            r = run(batch + ["-o", str(out)], env={"HQVIEW_FAULT_POINT": what})
            killed = r.returncode == -signal.SIGKILL
            label = f"SIGKILL at fault point {what}"
            check(killed, f"{label}: the run was killed there (exit {r.returncode})")
        else:
            p = subprocess.Popen(batch + ["-o", str(out)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            time.sleep(what)
            p.send_signal(signal.SIGKILL)
            p.wait()
            killed = p.returncode == -signal.SIGKILL
            label = f"SIGKILL after {what:.3f} s"
        killed_before_end += killed
        partial = complete_or_absent(out, ref, bundles)
        check(not partial, f"{label}: every bundle complete or absent" + (f" (partial: {partial})" if partial else ""))
        r = run(batch + ["-o", str(out), "--resume"])
        differ = outputs_equal(out, ref, bundles) if (out / "index.json").exists() else ["index.json missing"]
        check(not differ, f"{label}: --resume finishes the work, outputs byte-identical" + (f" (differ: {differ})" if differ else ""))
        left = leftovers(out)
        check(not left, f"{label}: no temporary left after the resumed run" + (f" ({left[:3]})" if left else ""))
    print(f"      {len(trials)} kill trials, {killed_before_end} killed before the run ended", flush=True)


def signal_stops(hq, mesh, work, args):
    out = work / "signal_out"
    shutil.rmtree(out, ignore_errors=True)
    base = [hq, "analyze", str(mesh), "-o", str(out), "--quiet"] + ([] if args.render else ["--no-render"])
    r = run(base)
    before = (out / "report.json").read_bytes() if r.returncode == 0 else None
    check(before is not None, "signals: a first bundle to keep")
    # The signals land at fractions of the other mesh's own run time (it
    # changes with the machine and with every speed-up).
    t = time.monotonic()
    run(base[:2] + [str(args.other_mesh), "-o", str(work / "signal_timing")] + base[5:])
    duration = time.monotonic() - t
    shutil.rmtree(work / "signal_timing", ignore_errors=True)
    fractions = [0.25, 0.5, 0.75] if not args.full else [k / 30 for k in range(1, 30)]
    for sig, code in [(signal.SIGINT, 130), (signal.SIGTERM, 143)]:
        for delay in [f * duration for f in fractions]:
            # Another mesh, so that a finished run would change report.json.
            p = subprocess.Popen(base[:2] + [str(args.other_mesh)] + base[3:], stderr=subprocess.PIPE, text=True)
            time.sleep(delay)
            if p.poll() is not None:  # finished first: it replaced the bundle; make the first one again
                p.communicate()
                run(base)
                before = (out / "report.json").read_bytes()
                continue
            t = time.monotonic()
            p.send_signal(sig)
            err = p.communicate()[1]
            latency = time.monotonic() - t
            name = signal.Signals(sig).name
            if p.returncode == 0 and "stopped by" not in err:
                # Past its last poll point (the bundle writer polls just
                # before it swaps the bundle in) the run finishes. Arriving
                # before main's exit, the signal is named ("arrived after the
                # work was complete"); later, during the process's teardown,
                # nothing can name it, and the process must be gone at once.
                named = "arrived after the work was complete" in err
                check((named or latency < 0.05) and latency < 1.0
                      and not leftovers(work / "signal_out") and (out / "report.json").exists(),
                      f"{name} after {delay:.2f} s: arrived after the last poll point (exit 0 within "
                      f"{latency:.3f} s; {'named' if named else 'not named: teardown, < 0.05 s'}); the new bundle is whole")
                run(base)
                before = (out / "report.json").read_bytes()
                continue
            # Before main() has installed the handler (the first ~50 ms: the
            # dynamic loader) the signal's default action ends the process,
            # which a shell also reports as 128 + the signal.
            early = p.returncode == -sig and "stopped by" not in err
            check((p.returncode == code and "stopped by " + name in err or early) and latency < 1.0,
                  f"{name} after {delay:.2f} s: exit {p.returncode} (want {code}{', killed before main' if early else ''}) "
                  f"within {latency:.3f} s (< 1 s)")
            check(not leftovers(work / "signal_out") and not leftovers(work) and (out / "report.json").read_bytes() == before,
                  f"{name} after {delay:.2f} s: previous bundle intact, no temporary left")


def disk_full(hq, small, large, work):
    out = work / "full"
    shutil.rmtree(out, ignore_errors=True)
    run([hq, "analyze", str(small), "-o", str(out / "b"), "--no-render", "--quiet"])
    before = (out / "b" / "report.json").read_bytes()
    r = run([hq, "analyze", str(large), "-o", str(out / "b"), "--no-render"], limit_fsize=20 * 1024)
    check(r.returncode == 5 and "File too large" in r.stderr and str(out) in r.stderr and "please report" not in r.stderr,
          f"file size limit: exit {r.returncode} (want 5), message names the path and the cause: {r.stderr.strip()[:160]}")
    check((out / "b" / "report.json").read_bytes() == before and not leftovers(out),
          "file size limit: previous bundle intact, no temporary left")
    # A small tmpfs where mounting is allowed (root on a machine that permits it).
    mnt = work / "tmpfs"
    mnt.mkdir(exist_ok=True)
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", str(mnt)], capture_output=True).returncode == 0:
        try:
            r = run([hq, "analyze", str(large), "-o", str(mnt / "b"), "--no-render"])
            check(r.returncode == 5 and "No space left on device" in r.stderr and "please report" not in r.stderr,
                  f"tmpfs full: exit {r.returncode} (want 5): {r.stderr.strip()[:160]}")
            check(not leftovers(mnt) and not (mnt / "b").exists(), "tmpfs full: nothing half-written left")
        finally:
            subprocess.run(["umount", str(mnt)])
    else:
        print("skip  tmpfs: mounting is not allowed here (the file size limit above stands for it)", flush=True)


def batch_disk_full(hq, collection, work):
    out = work / "batch_full"
    shutil.rmtree(out, ignore_errors=True)
    # 200 KiB per file: the small meshes' bundles fit, the large ones' annotated.vtu does not.
    r = run([hq, "batch", str(collection), "-o", str(out), "--no-render", "--quiet"], limit_fsize=200 * 1024)
    index = json.loads((out / "index.json").read_text()) if (out / "index.json").exists() else {"meshes": []}
    failed = [m for m in index["meshes"] if m["status"] == "failed"]
    ok = [m for m in index["meshes"] if m["status"] != "failed"]
    check(r.returncode == 5 and failed and ok and all("File too large" in m["error"] for m in failed),
          f"batch under a file size limit: exit {r.returncode} (want 5), {len(failed)} meshes failed with the cause, {len(ok)} analysed")
    check(not leftovers(out), "batch under a file size limit: no temporary left")


def read_only_and_loops(hq, small, collection, work):
    ro = work / "readonly"
    shutil.rmtree(ro, ignore_errors=True)
    ro.mkdir()
    if subprocess.run(["chattr", "+i", str(ro)], capture_output=True).returncode == 0:
        try:
            r = run([hq, "analyze", str(small), "-o", str(ro / "b"), "--no-render"])
            check(r.returncode == 5 and "Operation not permitted" in r.stderr and "please report" not in r.stderr,
                  f"immutable output directory: exit {r.returncode} (want 5): {r.stderr.strip()[:160]}")
        finally:
            subprocess.run(["chattr", "-i", str(ro)])
        # batch: one subfolder immutable, the others analysed.
        out = work / "batch_ro"
        shutil.rmtree(out, ignore_errors=True)
        run([hq, "batch", str(collection), "-o", str(out), "--no-render", "--quiet"])
        sub = sorted(p for p in out.iterdir() if p.is_dir())[0]
        shutil.rmtree(sub)
        sub.mkdir()
        subprocess.run(["chattr", "+i", str(sub)])
        try:
            r = run([hq, "batch", str(collection), "-o", str(out), "--no-render", "--quiet"])
            index = json.loads((out / "index.json").read_text())
            failed = {m["path"] for m in index["meshes"] if m["status"] == "failed"}
            inside = {m["path"] for m in index["meshes"] if m["path"].startswith(sub.name + "/")}
            check(r.returncode == 5 and failed == inside and len(failed) < len(index["meshes"]),
                  f"batch with an immutable subfolder: exit {r.returncode} (want 5), failed exactly its {len(inside)} meshes")
        finally:
            subprocess.run(["chattr", "-i", str(sub)])
    else:
        print("skip  read-only output: chattr +i is not supported on this file system", flush=True)
    loop = work / "loop"
    if loop.is_symlink():
        loop.unlink()
    loop.symlink_to("loop")
    r = run([hq, "analyze", str(small), "-o", str(loop / "b"), "--no-render"])
    check(r.returncode == 5 and "Too many levels of symbolic links" in r.stderr,
          f"output through a symlink loop: exit {r.returncode} (want 5): {r.stderr.strip()[:160]}")


def inputs_changing(hq, data, work):
    """A mesh deleted and one truncated while the batch runs: those two fail, the others are analysed."""
    src = work / "changing_src"
    shutil.rmtree(src, ignore_errors=True)
    src.mkdir()
    big = data / "gao2016_sweeping" / "Dolphin_padded.mesh"
    shutil.copy(big, src / "a_big.mesh")
    for name in ["b_deleted", "c_truncated", "d_kept"]:
        shutil.copy(data / "gao2016_sweeping" / "bunny_1.mesh", src / (name + ".mesh"))
    out = work / "changing_out"
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.Popen([hq, "batch", str(src), "-o", str(out), "-j", "1", "--no-render", "--quiet"],
                         stderr=subprocess.PIPE, text=True)
    # The marker appears once the collection is listed; then the big mesh is
    # analysed (0.5 s) while the others wait.
    deadline = time.monotonic() + 30
    while not (out / ".hqview-batch").exists() and time.monotonic() < deadline:
        time.sleep(0.005)
    (src / "b_deleted.mesh").unlink()
    text = (src / "c_truncated.mesh").read_bytes()
    (src / "c_truncated.mesh").write_bytes(text[: len(text) // 2])
    p.communicate()
    index = json.loads((out / "index.json").read_text())
    status = {m["path"]: (m["status"], m["error"] or "") for m in index["meshes"]}
    check(p.returncode == 3 and status["a_big.mesh"][0] == "ok" and status["d_kept.mesh"][0] == "ok"
          and status["b_deleted.mesh"][0] == "failed" and status["c_truncated.mesh"][0] == "failed"
          and "b_deleted.mesh" in status["b_deleted.mesh"][1] and "c_truncated.mesh:" in status["c_truncated.mesh"][1],
          f"inputs deleted and truncated during the batch: exit {p.returncode}, {status}")


def concurrent_writers(hq, mesh_a, mesh_b, work):
    refs = {}
    for name, mesh in [("a", mesh_a), ("b", mesh_b)]:
        refs[name] = work / ("conc_ref_" + name)
        shutil.rmtree(refs[name], ignore_errors=True)
        run([hq, "analyze", str(mesh), "-o", str(refs[name]), "--no-render", "--quiet"])
    out = work / "conc_out"
    shutil.rmtree(out, ignore_errors=True)
    for round_ in range(4):
        procs = [subprocess.Popen([hq, "analyze", str(m), "-o", str(out), "--no-render", "--quiet"],
                                  stderr=subprocess.PIPE) for m in (mesh_a, mesh_b)]
        codes = [p.wait() for p in procs]
        files = [f for f in files_of(out) if f != "timings.json"]
        whole = [n for n, ref in refs.items()
                 if files == [f for f in files_of(ref) if f != "timings.json"]
                 and all(same_bytes(out / f, ref / f) for f in files)]
        check(all(c in (0, 2, 5) for c in codes) and len(whole) == 1 and not leftovers(work),
              f"two analyze runs writing one -o at once (round {round_ + 1}): exits {codes}, the bundle is wholly {whole}")


def mesh_timeout(hq, data, work):
    src = work / "timeout_src"
    shutil.rmtree(src, ignore_errors=True)
    src.mkdir()
    shutil.copy(data / "gao2016_sweeping" / "Dolphin_padded.mesh", src / "slow.mesh")
    shutil.copy(data / "gao2016_sweeping" / "bunny_1.mesh", src / "fast.mesh")
    out = work / "timeout_out"
    shutil.rmtree(out, ignore_errors=True)
    r = run([hq, "batch", str(src), "-o", str(out), "-j", "1", "--no-render", "--quiet", "--mesh-timeout", "0.1"])
    index = json.loads((out / "index.json").read_text())
    status = {m["path"]: (m["status"], m["error"]) for m in index["meshes"]}
    junit = (out / "junit.xml").read_text()
    check(r.returncode == 3 and status["slow.mesh"] == ("failed", "stopped after 0.1 s (--mesh-timeout)")
          and status["fast.mesh"][0] == "ok" and 'name="slow.mesh"' in junit and "--mesh-timeout" in junit
          and not (out / "slow.mesh").exists() and not leftovers(out),
          f"--mesh-timeout 0.1: the slow mesh failed with the reason, the other analysed (exit {r.returncode}, {status})")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("hqview")
    ap.add_argument("data")
    ap.add_argument("work")
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--render", action="store_true")
    ap.add_argument("--trials", type=int, default=None)
    ap.add_argument("--seed", type=int, default=21)
    args = ap.parse_args()
    hq = str(Path(args.hqview).resolve())
    data = Path(args.data).resolve() / "meshes"
    if not data.is_dir():
        print("skip: no shared data at " + str(data))
        return 77
    work = Path(args.work).resolve()
    work.mkdir(parents=True, exist_ok=True)
    if args.trials is None:
        args.trials = 20 if args.full else 3
    rng = random.Random(args.seed)
    small = data / "gao2016_sweeping" / "bunny_1.mesh"
    large = data / "gao2016_sweeping" / "Dolphin_padded.mesh"
    args.other_mesh = large
    if args.full:
        collection = data
    else:
        collection = work / "small_collection"
        shutil.rmtree(collection, ignore_errors=True)
        for rel in ["gao2016_sweeping/bunny_1.mesh", "gao2016_sweeping/hand7_1.mesh", "li2012_srf/fandisk.mesh",
                    "smf2019/hex_cube_coarse.vtk", "gao2016_sweeping/Dolphin_padded.mesh"]:
            (collection / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(data / rel, collection / rel)
    kill_trials(hq, collection, work, args, rng)
    signal_stops(hq, small, work, args)
    disk_full(hq, small, large, work)
    batch_disk_full(hq, collection, work)
    read_only_and_loops(hq, small, collection, work)
    inputs_changing(hq, data, work)
    concurrent_writers(hq, small, data / "li2012_srf" / "fandisk.mesh", work)
    mesh_timeout(hq, data, work)
    print(f"{len(FAILURES)} failed" if FAILURES else "all fault checks passed", flush=True)
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
