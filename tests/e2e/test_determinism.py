"""Same input, same output: the po-plain chain run twice gives the same bytes (docs/cli.md, "Determinism").

    /usr/bin/python3 tests/e2e/test_determinism.py BUILD_DIR WORK_DIR [--seed N] [--first-run DIR]

1. Runs `make demo SCALE=tiny` (every tool: plan, mesh, faults, flow, continuous and faulted
   mechanics, sampling, calibration with concurrent solver runs, report) twice into the same output
   path: once undisturbed, once with every process of the chain stopped (SIGSTOP) and continued
   (SIGCONT) at random moments, as a busy machine would. Every output file must be byte-identical; only
   the *.log files and the calibration cache's timing.txt, which hold wall-clock timings on purpose,
   are left out of the comparison. With --first-run DIR, the undisturbed run is the one already in DIR
   (the end-to-end test's, made with the same command): it is moved aside and the paused run writes to
   the same path, so both runs see the same file names.
2. Runs the mechanics of the chain's first run on 2 MPI processes twice with the default solver (one run
   paused in the same way) and compares the results byte for byte: a given process count gives the
   same bytes.

The pauses come from a seeded generator (--seed, printed), so a failure can be replayed. Exit 0 when
every file matches; otherwise prints each differing file and exits 1.
"""

import argparse
import filecmp
import os
import random
import shutil
import signal
import subprocess
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SAMPLE = os.path.join(ROOT, "data-samples", "po-plain")
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


class Pauser(threading.Thread):
    """Stops and continues a process group at random moments until told to stop."""

    def __init__(self, pgid, rng):
        super().__init__(daemon=True)
        self.pgid, self.rng = pgid, rng
        self.done = threading.Event()
        self.pauses = 0

    def run(self):
        while not self.done.wait(self.rng.uniform(0.2, 2.0)):
            try:
                os.killpg(self.pgid, signal.SIGSTOP)
            except ProcessLookupError:
                return
            self.pauses += 1
            time.sleep(self.rng.uniform(0.05, 0.4))
            try:
                os.killpg(self.pgid, signal.SIGCONT)
            except ProcessLookupError:
                return
        try:
            os.killpg(self.pgid, signal.SIGCONT)
        except ProcessLookupError:
            pass


def run(cmd, env, rng=None, cwd=None):
    """Runs cmd in its own process group, paused at random moments when rng is given."""
    t0 = time.time()
    p = subprocess.Popen(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    pauser = None
    if rng is not None:
        pauser = Pauser(p.pid, rng)
        pauser.start()
    out, err = p.communicate()
    if pauser:
        pauser.done.set()
        pauser.join()
    return p.returncode, out, err, time.time() - t0, (pauser.pauses if pauser else 0)


def tree_files(top):
    files = []
    for d, _, names in os.walk(top):
        for n in names:
            files.append(os.path.relpath(os.path.join(d, n), top))
    return sorted(files)


def compare_trees(a, b, what):
    fa, fb = tree_files(a), tree_files(b)
    check(fa == fb, f"{what}: the same {len(fa)} files in both runs"
          + ("" if fa == fb else f" (only first: {sorted(set(fa) - set(fb))[:5]}, only second: {sorted(set(fb) - set(fa))[:5]})"))
    compared = differ = 0
    for f in sorted(set(fa) & set(fb)):
        if f.endswith(".log") or os.path.basename(f) == "timing.txt":
            continue  # wall-clock timings, on purpose
        compared += 1
        if not filecmp.cmp(os.path.join(a, f), os.path.join(b, f), shallow=False):
            differ += 1
            check(False, f"{what}: {f} is byte-identical")
    check(compared > 0 and differ == 0, f"{what}: {compared - differ} of {compared} output files byte-identical")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("work")
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--first-run", help="an undisturbed run of the same make command already made (OUT=DIR)")
    a = ap.parse_args()
    build, work = os.path.abspath(a.build), os.path.abspath(a.work)
    seed = a.seed if a.seed is not None else random.SystemRandom().randrange(1 << 31)
    print(f"seed {seed} (replay with --seed {seed})", flush=True)
    rng = random.Random(seed)
    env = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", PYTHONDONTWRITEBYTECODE="1", GDAL_PAM_ENABLED="NO")
    out = os.path.abspath(a.first_run) if a.first_run else os.path.join(work, "out")
    run1, run2 = os.path.join(work, "run1"), os.path.join(work, "run2")
    make = ["make", "-s", "-j2", "-C", SAMPLE, f"UGS_BIN={build}/tools", f"OUT={out}", "SCALE=tiny", "demo"]

    for d in (run1, run2):
        shutil.rmtree(d, ignore_errors=True)
    os.makedirs(work, exist_ok=True)
    runs = [("paused", run2, rng)]
    if a.first_run and os.path.isfile(os.path.join(out, "report", "summary.md")):
        os.rename(out, run1)
    else:
        shutil.rmtree(out, ignore_errors=True)
        runs.insert(0, ("undisturbed", run1, None))
    for name, dest, r in runs:
        code, so, se, secs, pauses = run(make, env, r)
        check(code == 0, f"make demo SCALE=tiny ({name}) exits 0 ({secs:.0f} s, {pauses} pauses)"
              + ("" if code == 0 else f": {se.strip()[-2000:]}"))
        if code != 0:
            return
        os.rename(out, dest)
    compare_trees(run1, run2, "serial chain")

    # The mechanics on 2 processes with the default solver (CG + BoomerAMG), twice, one run paused.
    # (Not MUMPS: its parallel factorization schedules fronts dynamically, by the processes' measured
    # load, so the order of its sums follows message timing: round-off differences, docs/cli.md.)
    solve = os.path.join(build, "tools", "ugs-solve", "ugs-solve")
    # Both runs write to the same path (then moved aside): the CSVs' comments hold the command line.
    mpi = [os.path.join(work, "mpi1"), os.path.join(work, "mpi2")]
    d = os.path.join(work, "mpi")
    for i, dest in enumerate(mpi):
        shutil.rmtree(dest, ignore_errors=True)
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
        cmd = ["mpirun", "-n", "2", solve, os.path.join(run1, "model.msh"), "--case", "case.toml",
               "--pressure", os.path.join(run1, "pool_a_dp.h5"), "--pressure", os.path.join(run1, "pool_c_dp.h5"),
               "--until", "2003-04-01", "--solver", "cg-hypre", "-o", os.path.join(d, "solve.h5"),
               "--state", os.path.join(d, "state.h5"), "-q"]
        code, so, se, secs, pauses = run(cmd, env, rng if i == 1 else None, cwd=SAMPLE)
        check(code == 0, f"ugs-solve on 2 processes, run {i + 1} exits 0 ({secs:.0f} s, {pauses} pauses)"
              + ("" if code == 0 else f": {se.strip()[-2000:]}"))
        if code != 0:
            return
        os.rename(d, dest)
    compare_trees(mpi[0], mpi[1], "2 processes")


if __name__ == "__main__":
    main()
    print(f"{'FAILED' if failures else 'passed'}: {len(failures)} failure(s)")
    sys.exit(1 if failures else 0)
