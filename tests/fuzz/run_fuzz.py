#!/usr/bin/env python3
"""Builds the clang fuzz tree and runs every libFuzzer target on its seed corpus (docs/fuzzing.md).

    run_fuzz.py --source SRC --build DIR [--cc clang-14 --cxx clang++-14] [--seconds 5 | --fixed-runs] [--jobs 2]
                [--targets msh,csv] [--no-build]

Each target runs -max_total_time=SECONDS -seed=1 (--fuzz-seed) on corpus/<target> (read only: new inputs go to
DIR/corpus/<target>, crashes to DIR/artifacts/), with -rss_limit_mb=2048 -timeout=10 and the
target's dictionary when there is one. Exit status 1 and the crashing inputs listed when any target
reports a finding (crash, ASan/UBSan report, leak, uncaught exception, timeout, out of memory).
"""

import argparse
import os
import shutil
import subprocess
import sys
import time

TARGETS = ["msh", "hdf5_fields", "csv", "ps", "case_file", "schedule", "strata", "ogr", "ensemble_spec", "case_params",
           "horizon_grid", "tsurf", "zmap", "seismicity", "grdecl", "fault_sticks"]
# --fixed-runs (the test suite's run): a fixed number of executions per target instead of a time, so
# that with the fixed seed the same inputs are tried on a fast and on a busy machine and the suite
# cannot turn red by chance. About 5 s of each target on a busy 2-core machine.
FIXED_RUNS = {"msh": 60000, "hdf5_fields": 1000, "csv": 20000, "ps": 400, "case_file": 300, "schedule": 400,
              "strata": 600, "ogr": 1200,
              "ensemble_spec": 600, "case_params": 50, "horizon_grid": 400, "tsurf": 600, "zmap": 400, "seismicity": 150,
              "grdecl": 20000, "fault_sticks": 1000}
DICTS = {"msh": "msh.dict", "case_file": "toml.dict", "strata": "toml.dict", "ogr": "geojson.dict",
         "csv": "csv.dict", "ps": "csv.dict", "schedule": "csv.dict", "ensemble_spec": "ensemble.dict",
         "case_params": "case_params.dict", "horizon_grid": "horizon.dict", "tsurf": "horizon.dict",
         "zmap": "horizon.dict", "seismicity": "csv.dict"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--cc", default="clang-14")
    ap.add_argument("--cxx", default="clang++-14")
    ap.add_argument("--seconds", type=int, default=5)
    ap.add_argument("--fixed-runs", action="store_true", help="FIXED_RUNS executions per target, not --seconds")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--targets", default=",".join(TARGETS))
    ap.add_argument("--no-build", action="store_true")
    ap.add_argument("--fuzz-seed", type=int, default=1,
                    help="libFuzzer -seed (1: the same mutations every run, as in CI; 0: a new seed each run)")
    a = ap.parse_args()
    here = os.path.join(a.source, "tests", "fuzz")
    targets = [t for t in a.targets.split(",") if t]

    if not a.no_build:
        t0 = time.time()
        cfg = ["cmake", "-S", a.source, "-B", a.build, "-DUGS_FUZZ=ON", "-DCMAKE_BUILD_TYPE=Debug",
               f"-DCMAKE_C_COMPILER={a.cc}", f"-DCMAKE_CXX_COMPILER={a.cxx}"]
        if shutil.which("ccache"):
            cfg += ["-DCMAKE_C_COMPILER_LAUNCHER=ccache", "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"]
        for cmd in (cfg, ["cmake", "--build", a.build, "-j", str(a.jobs), "--target", "ugs_fuzz_targets"]):
            r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            if r.returncode != 0:
                print(r.stdout[-6000:])
                print(f"FAIL: {' '.join(cmd)} exited {r.returncode}")
                return 1
        print(f"fuzz tree built in {time.time() - t0:.0f} s ({a.build})")

    env = dict(os.environ)
    # Leaks are findings; UBSan stops at the first report (the tree is built with
    # -fno-sanitize-recover=undefined); ASan reports go to stderr, kept in the log.
    # allocator_may_return_null: a damaged HDF5 header makes libhdf5 itself ask malloc for absurd sizes
    # (6e16 bytes, in H5C_protect); a real malloc returns NULL there, HDF5 fails and the reader must
    # turn that into an InputError. ASan's default would abort inside libhdf5 and hide that path.
    env["ASAN_OPTIONS"] = ("detect_leaks=1:abort_on_error=0:symbolize=1:allocator_may_return_null=1:"
                           + env.get("ASAN_OPTIONS", ""))
    env["UBSAN_OPTIONS"] = "print_stacktrace=1:halt_on_error=1:" + env.get("UBSAN_OPTIONS", "")
    supp = os.path.join(here, "lsan.supp")
    if os.path.exists(supp):
        env["LSAN_OPTIONS"] = f"suppressions={supp}:" + env.get("LSAN_OPTIONS", "")
    env.setdefault("GDAL_PAM_ENABLED", "NO")

    findings = []
    for t in targets:
        exe = os.path.join(a.build, f"fuzz_{t}")
        seeds = os.path.join(here, "corpus", t)
        work = os.path.join(a.build, "corpus", t)
        arts = os.path.join(a.build, "artifacts")
        if a.fixed_runs:
            shutil.rmtree(work, ignore_errors=True)  # the same start every time: the same inputs tried
        os.makedirs(work, exist_ok=True)
        os.makedirs(arts, exist_ok=True)
        budget = [f"-runs={FIXED_RUNS[t]}", "-max_total_time=600"] if a.fixed_runs else [f"-max_total_time={a.seconds}"]
        cmd = [exe] + budget + ["-rss_limit_mb=2048", "-timeout=10",
               f"-artifact_prefix={arts}/{t}-", "-print_final_stats=1", f"-seed={a.fuzz_seed}"]
        if t in DICTS:
            cmd.append("-dict=" + os.path.join(here, "dict", DICTS[t]))
        cmd += [work, seeds]
        log = os.path.join(a.build, f"fuzz_{t}.log")
        before = set(os.listdir(arts))
        t0 = time.time()
        with open(log, "w") as fh:
            r = subprocess.run(cmd, stdout=fh, stderr=subprocess.STDOUT, env=env, cwd=a.build,
                               timeout=(600 if a.fixed_runs else a.seconds) + 300)
        with open(log, errors="replace") as fh:
            text = fh.read()
        execs = next((ln.rsplit(":", 1)[1].strip() for ln in text.splitlines()
                      if ln.startswith("stat::number_of_executed_units")), "?")
        new = sorted(set(os.listdir(arts)) - before)
        ok = r.returncode == 0 and not new
        print(f"{'ok  ' if ok else 'FAIL'} fuzz_{t}: {execs} runs in {time.time() - t0:.0f} s, exit {r.returncode}"
              + (f", artifacts {', '.join(new)}" if new else ""))
        if not ok:
            lines = [ln for ln in text.splitlines() if "ERROR" in ln or "SUMMARY" in ln or "==" in ln[:3]]
            print("\n".join("    " + ln for ln in lines[:12]))
            print(f"    log: {log}")
            print(f"    replay: {exe} {' '.join(os.path.join(arts, n) for n in new)}")
            findings.append(t)
    if findings:
        print(f"FAIL: findings in {', '.join(findings)} (docs/fuzzing.md: each finding is a bug)")
        return 1
    print(f"ok: {len(targets)} fuzz targets, no finding")
    return 0


if __name__ == "__main__":
    sys.exit(main())
