#!/usr/bin/python3
"""workflow/Snakefile with the repository's Slurm profile against a real,
one-node Slurm (issue 49; docs/collections.md "Slurm"): Debian's slurm-wlm
22.05 and munge, started here as root on free loopback ports and stopped at
the end whatever happens.

- The cluster: munged, slurmctld and slurmd in the foreground as this
  process's children, their files in WORKDIR; ProctrackType=proctrack/linuxproc,
  TaskPlugin=task/none, no accounting database but
  JobCompType=jobcomp/filetxt (one record per finished job). The node claims
  4 CPUs and 16,000 MB whatever the machine has (SlurmdParameters=
  config_overrides) and the partition is called `normal`, so the profile's
  requests (analyze: 2 CPUs, 4,000 MB; index: 4 CPUs, 8,000 MB; partition
  normal) are submitted unchanged. MinJobAge=3600: without accounting,
  Snakemake's job status falls back to `scontrol`, which forgets a job
  MinJobAge seconds after it ends.
- A guard process outside this process's tree stops the daemons when this
  process dies without cleaning up (a CTest timeout's SIGKILL); every wait is
  bounded (DEADLINE seconds in all).
- Run 1: Snakemake (with USER unset, as in a container) over a few small
  meshes; one COMPLETED record per mesh and one for the index; the output
  equals `hqview batch`'s byte for byte (timings.json aside).
- Run 2: a wrapper holds one mesh's job until it is cancelled; scancel; the
  record says CANCELLED, Snakemake fails and writes no index; run 3, the same
  command, submits that mesh and the index only and finishes the collection,
  byte-identical to the batch.

usage: check_slurm.py HQVIEW SOURCE_DIR SHARED_DATA WORKDIR
Exit 77 without root, Slurm, munge, Snakemake or the shared data.
"""
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from check_workflows import tree_differences  # noqa: E402

FAILURES = []
DEADLINE = 420  # seconds for the whole test (CTest's TIMEOUT is 600)
START = time.monotonic()


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        FAILURES.append(what)


def left():
    return max(1.0, DEADLINE - (time.monotonic() - START))


def free_ports(n):
    socks = []
    for _ in range(n):
        s = socket.socket()
        s.bind(("127.0.0.1", 0))
        socks.append(s)
    ports = [s.getsockname()[1] for s in socks]
    for s in socks:
        s.close()
    return ports


class Cluster:
    """munged + slurmctld + slurmd, one node, in `root` (a fresh directory)."""

    def __init__(self, root):
        self.root = root
        shutil.rmtree(root, ignore_errors=True)
        for d in ("munge", "state", "spool", "log"):
            (root / d).mkdir(parents=True)
        (root / "munge").chmod(0o700)
        key = root / "munge" / "munge.key"
        key.write_bytes(os.urandom(1024))
        key.chmod(0o400)
        self.socket = root / "munge" / "munge.socket"
        self.conf = root / "slurm.conf"
        self.jobcomp = root / "jobcomp.txt"
        host = socket.gethostname().split(".")[0]
        ctld_port, d_port = free_ports(2)
        r = root
        self.conf.write_text(f"""# tests/workflow/check_slurm.py: a one-node Slurm for one test
ClusterName=hqviewtest
SlurmctldHost={host}(127.0.0.1)
SlurmctldPort={ctld_port}
SlurmdPort={d_port}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={self.socket}
StateSaveLocation={r}/state
SlurmdSpoolDir={r}/spool
SlurmctldPidFile={r}/slurmctld.pid
SlurmdPidFile={r}/slurmd.pid
SlurmctldLogFile={r}/log/slurmctld.log
SlurmdLogFile={r}/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SlurmdParameters=config_overrides
JobCompType=jobcomp/filetxt
JobCompLoc={self.jobcomp}
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MinJobAge=3600
ReturnToService=2
NodeName={host} NodeAddr=127.0.0.1 CPUs=4 RealMemory=16000 State=UNKNOWN
PartitionName=normal Nodes=ALL Default=YES MaxTime=INFINITE State=UP
""")
        self.env = dict(os.environ, SLURM_CONF=str(self.conf))
        self.daemons = []
        self.pids_file = root / "daemons.pids"
        self.pids_file.write_text("")

    def start(self):
        # The guard: outside this process's tree (setsid -f), it stops the
        # daemons (and their jobs) once this process is gone, unless `done`
        # says the cleanup ran.
        guard = (f"while kill -0 {os.getpid()} 2>/dev/null; do sleep 1; done; "
                 f"[ -e '{self.root}/done' ] && exit 0; "
                 f"SLURM_CONF='{self.conf}' scancel --full --state=RUNNING,PENDING --user=root 2>/dev/null; sleep 2; "
                 f"for p in $(cat '{self.pids_file}'); do kill $p 2>/dev/null; done; sleep 5; "
                 f"for p in $(cat '{self.pids_file}'); do kill -9 $p 2>/dev/null; done")
        subprocess.run(["setsid", "-f", "sh", "-c", guard], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, check=True)
        m = self.root / "munge"
        self.spawn(["munged", "-F", "--force", f"--key-file={m}/munge.key", f"--socket={self.socket}",
                    f"--pid-file={m}/munged.pid", f"--log-file={self.root}/log/munged.log", f"--seed-file={m}/seed"])
        self.wait_for(lambda: self.socket.exists(), "munged's socket", 15)
        self.spawn(["slurmctld", "-D", "-f", str(self.conf)])
        self.wait_for(lambda: self.run(["scontrol", "ping"]).returncode == 0, "slurmctld answering", 30)
        self.spawn(["slurmd", "-D", "-f", str(self.conf)])
        self.wait_for(lambda: self.run(["sinfo", "-h", "-o", "%T"]).stdout.strip() == "idle", "the node idle", 60)

    def spawn(self, argv):
        log = open(self.root / "log" / (Path(argv[0]).name + ".out"), "w")
        p = subprocess.Popen(argv, env=self.env, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
        self.daemons.append(p)
        with open(self.pids_file, "a") as f:
            f.write(f"{p.pid}\n")

    def run(self, argv, timeout=30):
        return subprocess.run(argv, env=self.env, capture_output=True, text=True, timeout=min(timeout, left()))

    def wait_for(self, predicate, what, seconds):
        end = time.monotonic() + min(seconds, left())
        while time.monotonic() < end:
            for p in self.daemons:
                if p.poll() is not None:
                    raise RuntimeError(f"{p.args[0]} exited ({p.returncode}) while waiting for {what}: "
                                       + self.logs())
            try:
                if predicate():
                    return
            except subprocess.TimeoutExpired:
                pass
            time.sleep(0.5)
        raise RuntimeError(f"timed out waiting for {what}: " + self.logs())

    def logs(self):
        out = ""
        for f in sorted((self.root / "log").iterdir()):
            out += f"\n--- {f.name}\n" + f.read_text(errors="replace")[-1500:]
        return out

    def records(self):
        """jobcomp/filetxt's records: {JobId: {field: value}}."""
        recs = {}
        if self.jobcomp.exists():
            for line in self.jobcomp.read_text().splitlines():
                fields = dict(re.findall(r"(\w+)=(\S*)", line))
                if "JobId" in fields:
                    recs[fields["JobId"]] = fields
        return recs

    def stop(self):
        try:
            self.run(["scancel", "--full", "--user=root"], timeout=10)
            end = time.monotonic() + 20
            while time.monotonic() < end and self.run(["squeue", "-h"], timeout=5).stdout.strip():
                time.sleep(0.5)
        except Exception as e:  # the daemons may be gone already
            print(f"      (cleanup: {e})")
        for p in reversed(self.daemons):  # slurmd, slurmctld, munged
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait(5)
        # Job processes that outlived slurmd (slurmstepd reparents them): the
        # ones with this cluster's SLURM_CONF in their environment.
        mark = f"SLURM_CONF={self.conf}".encode()
        for proc in Path("/proc").iterdir():
            if proc.name.isdigit() and int(proc.name) != os.getpid():
                try:
                    if mark in (proc / "environ").read_bytes().split(b"\0"):
                        os.kill(int(proc.name), signal.SIGKILL)
                except (OSError, ProcessLookupError):
                    pass
        (self.root / "done").touch()


def slurm_logs(work, rule):
    """Snakemake's per-job logs: {slurm job id: text} of one rule."""
    d = work / ".snakemake" / "slurm_logs" / f"rule_{rule}"
    return {f.stem: f.read_text(errors="replace") for f in d.glob("*.log")} if d.is_dir() else {}


def run_checks(hq, source, data, work, cluster):
    coll = work / "collection"
    for rel in ["gao2016_sweeping/bunny_1.mesh", "li2012_srf/fandisk.mesh", "smf2019/hex_cube_coarse.vtk"]:
        (coll / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(data / rel, coll / rel)
    paths = ["gao2016_sweeping/bunny_1.mesh", "li2012_srf/fandisk.mesh", "smf2019/hex_cube_coarse.vtk"]
    options = "--no-render --gate quality.scaled_jacobian.min>=0.3"
    ref = work / "batch_out"
    subprocess.run([hq, "batch", str(coll), "-o", str(ref), "-j", "2", "--quiet"] + options.split(),
                   timeout=left())
    env = dict(cluster.env)
    env.pop("USER", None)  # as in a container; the Snakefile supplies it for Snakemake 7.21's slurm executor

    def snakemake(out, hqview, wd, background=False):
        argv = ["snakemake", "-s", str(source / "workflow" / "Snakefile"), "--directory", str(wd),
                "--profile", str(source / "workflow" / "profiles" / "slurm"),
                # Snakemake 7.21 polls a Slurm job's status every 33 s unless
                # told 1/s or less; the profile keeps that (a big cluster's
                # controller likes few queries), the test asks once a second.
                "--max-status-checks-per-second", "1",
                "--config", f"inputs={coll}", f"output={out}", f"hqview={hqview}", f"options={options}"]
        log = open(wd.parent / (wd.name + ".snakemake.log"), "a")
        p = subprocess.Popen(argv, env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        if background:
            return p
        try:
            return p.wait(left())
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGTERM)
            p.wait(30)
            raise

    # Run 1: the whole collection.
    wd1, out1 = work / "run1", work / "slurm_out"
    wd1.mkdir()
    t = time.monotonic()
    code = snakemake(out1, hq, wd1)
    seconds = time.monotonic() - t
    recs = cluster.records()
    analyze, index = slurm_logs(wd1, "analyze"), slurm_logs(wd1, "index")
    done = {p for p in paths if any(f"path={p}" in text for text in analyze.values())}
    check(code == 0, f"run 1: snakemake with the Slurm profile exit {code} in {seconds:.0f} s "
          + ("" if code == 0 else (wd1.parent / "run1.snakemake.log").read_text()[-1500:]))
    check(len(analyze) == len(paths) and done == set(paths)
          and all(recs.get(j, {}).get("JobState") == "COMPLETED" for j in analyze),
          f"run 1: one COMPLETED Slurm job per mesh ({ {j: recs.get(j, {}).get('JobState') for j in analyze} })")
    check(len(index) == 1 and all(recs.get(j, {}).get("JobState") == "COMPLETED" for j in index),
          f"run 1: one COMPLETED Slurm job for the index ({list(index)})")
    check(all(recs[j].get("Partition") == "normal" and "mem=4000M" in recs[j].get("Tres", "")
              and "cpu=2" in recs[j].get("Tres", "") for j in analyze if j in recs)
          and all("mem=8000M" in recs[j].get("Tres", "") and "cpu=4" in recs[j].get("Tres", "") for j in index if j in recs),
          "run 1: the jobs ran with the profile's partition, memory and CPUs")
    differ = tree_differences(out1, ref) if out1.is_dir() else ["(no output)"]
    check((out1 / "index.json").exists() and not differ,
          f"run 1: the output equals hqview batch's byte for byte, timings.json aside (differ: {differ[:5]})")

    # Run 2: one mesh's job held until cancelled.
    held = "li2012_srf/fandisk.mesh"
    flag, jobfile = work / "hold", work / "held.jobid"
    wrapper = work / "hqview-hold.sh"
    wrapper.write_text(f"""#!/bin/sh
# Holds the analyze job of {held} while {flag} exists (until the job is cancelled).
if [ "$1" = analyze ] && [ -e '{flag}' ]; then
  case "$*" in *'/{held} '*) echo "$SLURM_JOB_ID" > '{jobfile}'; while :; do sleep 1; done ;; esac
fi
exec '{hq}' "$@"
""")
    wrapper.chmod(0o755)
    flag.touch()
    wd2, out2 = work / "run2", work / "slurm_out2"
    wd2.mkdir()
    before = set(cluster.records())
    p = snakemake(out2, wrapper, wd2, background=True)
    try:
        cluster.wait_for(lambda: jobfile.exists() and jobfile.read_text().strip(), "the held job", 180)
        jobid = jobfile.read_text().strip()
        r = cluster.run(["scancel", jobid])
        check(r.returncode == 0, f"run 2: scancel {jobid}")
        code = p.wait(left())
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGTERM)
            p.wait(30)
    recs = cluster.records()
    check(recs.get(jobid, {}).get("JobState") == "CANCELLED", f"run 2: job {jobid} recorded CANCELLED")
    others = [j for j in slurm_logs(wd2, "analyze") if j != jobid]
    check(code != 0 and not (out2 / "index.json").exists() and len(others) == len(paths) - 1
          and all(recs.get(j, {}).get("JobState") == "COMPLETED" for j in others),
          f"run 2: snakemake failed (exit {code}), the other meshes completed, no index")
    # Run 3: the same command without the hold.
    flag.unlink()
    seen = set(slurm_logs(wd2, "analyze")) | set(slurm_logs(wd2, "index"))
    code = snakemake(out2, wrapper, wd2)
    recs = cluster.records()
    new_analyze = [j for j in slurm_logs(wd2, "analyze") if j not in seen]
    new_index = [j for j in slurm_logs(wd2, "index") if j not in seen]
    check(code == 0 and len(new_analyze) == 1 and f"path={held}" in slurm_logs(wd2, "analyze")[new_analyze[0]]
          and len(new_index) == 1 and all(recs.get(j, {}).get("JobState") == "COMPLETED" for j in new_analyze + new_index),
          f"run 3: the rerun submitted the cancelled mesh and the index only, both COMPLETED (exit {code}, "
          f"jobs {new_analyze} {new_index})")
    differ = tree_differences(out2, ref) if out2.is_dir() else ["(no output)"]
    check((out2 / "index.json").exists() and not differ,
          f"run 3: the collection is finished, byte-identical to hqview batch (differ: {differ[:5]})")
    check(len(set(recs) - before) == len(paths) + 2, f"runs 2-3: {len(set(recs) - before)} records "
          f"({len(paths)} meshes + the cancelled one + the index)")


def main():
    hq, source, data, work = sys.argv[1], Path(sys.argv[2]).resolve(), Path(sys.argv[3]) / "meshes", Path(sys.argv[4])
    hq = str(Path(hq).resolve())
    missing = [t for t in ("snakemake", "slurmctld", "slurmd", "munged", "sbatch", "setsid") if shutil.which(t) is None]
    if os.geteuid() != 0 or missing or not data.is_dir():
        print(f"skip: needs root, {' '.join(missing) or 'the tools'} and the shared data")
        return 77
    work = work.resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    cluster = Cluster(work / "cluster")
    # SIGTERM (CTest, a CI runner cancelling) and SIGINT run the cleanup too.
    for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(s, lambda n, _f: (_ for _ in ()).throw(KeyboardInterrupt(f"signal {n}")))
    try:
        cluster.start()
        run_checks(hq, source, data.resolve(), work, cluster)
    except (Exception, KeyboardInterrupt) as e:  # noqa: B902 -- whatever it is, the cluster stops below
        check(False, f"the Slurm test stopped: {type(e).__name__}: {e}")
    finally:
        cluster.stop()
    print(f"{len(FAILURES)} failed ({time.monotonic() - START:.0f} s)" if FAILURES
          else f"all Slurm checks passed ({time.monotonic() - START:.0f} s)")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
