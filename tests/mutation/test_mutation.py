#!/usr/bin/env python3
"""Seeded mutation test of every tool (issue 20; docs/fuzzing.md).

    test_mutation.py BUILD_DIR WORK_DIR [--seed N] [--jobs J] [--tools flow,solve] [--scale X]
    test_mutation.py BUILD_DIR WORK_DIR --replay TOOL:SEED     (one run, its folder kept, command printed)

Makes a small valid chain once (fixtures.py: plan, layered mesh with a dipping fault, faulted mesh, flow
sub-mesh, pressure change, mechanics, samples), then runs each tool many times, each run on the
valid inputs with ONE input mutated by a seeded rule: bytes flipped, truncated, emptied, a number
replaced by inf / nan / -1 / 1e308 / "abc" / ..., a line deleted or duplicated, a 4- or 8-byte word
set to all ones, a directory in place of the file. Every run must satisfy:
  - the exit code is 0, 1 or 2: never a signal (negative return code), never another code, no hang;
  - exit 2: exactly one line on stderr, starting "ugs-<tool>: error: ";
  - exit != 0: the output folder is left empty (no output, no temporary file or folder; only
    ugs-calibrate's cache may keep a failed solver run, on exit 1);
  - exit 0: no NaN or inf in the text outputs (CSV, TOML, Markdown, XDMF, stdout).
Each tool's unmutated command runs first and must exit 0 (the chain is valid). The summary gives runs
and failures per tool; each failure is listed with its replay command.
"""

import argparse
import concurrent.futures as cf
import os
import random
import re
import shlex
import shutil
import struct
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import fixtures  # noqa: E402

TEXT_EXT = (".csv", ".toml", ".geojson", ".json", ".txt")
ECLIPSE_EXT = (".EGRID", ".UNRST")
OUTPUT_TEXT_EXT = (".csv", ".toml", ".md", ".txt", ".xdmf")
NONFINITE = re.compile(r"(?<![A-Za-z0-9_])[-+]?(nan|inf|infinity)(?![A-Za-z0-9_])", re.IGNORECASE)
NUMBER = re.compile(rb"(?<![A-Za-z0-9_.])[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?(?![A-Za-z0-9_])")
REPLACEMENTS = [b"inf", b"-inf", b"nan", b"-1", b"0", b"1e308", b"-1e308", b"abc", b"4294967295",
                b"1e-300", b"", b"null", b"99999999999999999999"]
RUN_TIMEOUT = 180  # s: a run that takes longer is a hang


def tool_exe(build, tool):
    return os.path.join(build, "tools", f"ugs-{tool}", f"ugs-{tool}")


# ---- the tools and their inputs ------------------------------------------------------------------
# Each tool: weight (runs relative to the others), the input files it reads (names in the base folder),
# and its command (IN = folder of the inputs, OUT = output folder, SOLVE = ugs-solve).
def tool_specs():
    solve_cmd = ("{SOLVE} {mesh} --case {case} --pressure {IN}/pool_x_dp.h5 --until 1950-12-01 --top {out} "
                 "-o {dir}/solve.h5 --state none --solver cholmod -q")
    return {
        "meshinfo": (1.0, ["model.msh"], "{IN}/model.msh --convert {OUT}/model.vtu"),
        "mesh2d": (1.0, ["domain.geojson", "faults.geojson", "traces.geojson"],
                   "--domain {IN}/domain.geojson --fault {IN}/faults.geojson --refine {IN}/traces.geojson "
                   "--hmax 2500 -q -o {OUT}/plan.msh"),
        "mesh2d:lines": (0.5, ["domain.geojson", "sections.geojson", "traces.geojson"],
                         "--domain {IN}/domain.geojson --section {IN}/sections.geojson --trace {IN}/traces.geojson "
                         "--hmax 3000 -q -o {OUT}/plan.msh"),
        "meshgen": (1.0, ["plan.msh", "strata.toml", "traces.geojson", "aquifers.geojson", "faults.geojson"],
                    "{IN}/plan.msh --strata {IN}/strata.toml -q -o {OUT}/model.msh"),
        "meshgen:grids": (0.7, ["plan.msh", "strata_grids.toml", "res_top.irap", "res_base.ts", "deep.zmap",
                                "bottom.cps"],
                          "{IN}/plan.msh --strata {IN}/strata_grids.toml -q -o {OUT}/model.msh"),
        "faultinsert": (1.0, ["model.msh", "faults.geojson"],
                        "{IN}/model.msh --faults {IN}/faults.geojson -q -o {OUT}/faulted.msh"),
        "submesh": (1.0, ["model.msh", "case.toml"],
                    "{IN}/model.msh --case {IN}/case.toml --pool 'Pool X' -q -o {OUT}/pool_x.msh"),
        "flow": (1.0, ["pool_x.msh", "case.toml", "pressure_pool_x.csv"],
                 "{IN}/pool_x.msh --case {IN}/case.toml -q -o {OUT}/dp.h5"),
        "solve": (0.7, ["model.msh", "case.toml", "pool_x_dp.h5"],
                  "{IN}/model.msh --case {IN}/case.toml --pressure {IN}/pool_x_dp.h5 --solver cholmod "
                  "--until 1950-04-01 --state none -q -o {OUT}/solve.h5"),
        "solve:faulted": (0.3, ["faulted.msh", "case.toml", "pool_x_dp.h5"],
                          "{IN}/faulted.msh --case {IN}/case.toml --pressure {IN}/pool_x_dp.h5 --fault-solver mumps "
                          "--until 1950-03-01 --state none --top none -q -o {OUT}/faulted.h5"),
        "sample": (1.0, ["solve_top.h5", "measured.csv", "case.toml"],
                   "--results {IN}/solve_top.h5 --points {IN}/measured.csv --case {IN}/case.toml --at-ps-dates "
                   "--ascending 34/-10 --descending 39/-170 -q -o {OUT}/samples.csv"),
        "sample:ogr": (0.5, ["solve.h5", "model.msh", "ps_points.geojson", "case.toml"],
                       "--results {IN}/solve.h5 --mesh {IN}/model.msh --points {IN}/ps_points.geojson "
                       "--case {IN}/case.toml -q -o {OUT}/samples.csv"),
        "calibrate": (0.5, ["case.toml", "model.msh", "measured.csv", "pool_x_dp.h5"],
                      "--case {IN}/case.toml --mesh {IN}/model.msh --param material.pool_x.c_R=2:6 "
                      "--measured {IN}/measured.csv --scan 2 --max-evals 2 -q -o {OUT}/calibration "
                      "--solver-command " + shlex.quote(solve_cmd)),
        "ensemble:emit": (0.7, ["ensemble.toml", "case.toml", "model.msh", "measured.csv", "traces.geojson"],
                          "run --spec {IN}/ensemble.toml --case {IN}/case.toml --mesh {IN}/model.msh --measured {IN}/measured.csv "
                          "--inside {IN}/traces.geojson --phase p=1950-03-01/1950-09-01 --emit make --cache-dir {OUT}/members.cache "
                          "-q -o {OUT}/members.mk --solver-command " + shlex.quote(solve_cmd)),
        "seismicity": (0.5, ["pairs_fault_F.csv", "seismicity.toml"],
                       "{IN}/pairs_fault_F.csv --case {IN}/seismicity.toml --start 1950-02-01 --window 1950-02-01/1950-04-01 "
                       "-q -o {OUT}/forecast.csv"),
        "seismicity:patch": (0.3, ["dcfs.csv", "seismicity.toml"],
                             "{IN}/dcfs.csv --case {IN}/seismicity.toml --patch-name F --window 1950-03-01/1950-12-01 -q "
                             "-o {OUT}/patch.csv"),
        "import-eclipse": (0.7, ["TINY.EGRID", "TINY.UNRST", "deck_mesh.msh"],
                           "{IN}/TINY.EGRID --restart {IN}/TINY.UNRST --mesh {IN}/deck_mesh.msh -q -o {OUT}/dp.h5"),
        "report": (0.35, ["solve.h5", "solve_top.h5", "model.msh", "case.toml", "traces.geojson"],
                   "--results {IN}/solve.h5 --mesh {IN}/model.msh --case {IN}/case.toml --trace {IN}/traces.geojson "
                   "--width 400 --height 300 -q -o {OUT}/report"),
    }


def command(build, key, spec, in_dir, out_dir):
    args = spec[2].replace("{SOLVE}", tool_exe(build, "solve")).replace("{IN}", in_dir).replace("{OUT}", out_dir)
    return [tool_exe(build, tool_of(key))] + shlex.split(args)


def tool_of(key):
    """'solve:faulted' (a second way to run ugs-solve) -> 'solve'."""
    return key.split(":")[0]


# ---- the valid chain ---------------------------------------------------------------------------
def make_chain(build, base):
    os.makedirs(base, exist_ok=True)
    fixtures.write_inputs(base)
    b = lambda t: tool_exe(build, t)  # noqa: E731
    steps = [
        [b("mesh2d"), "--domain", "domain.geojson", "--fault", "faults.geojson", "--refine", "traces.geojson",
         "--hmax", "2500", "-q", "-o", "plan.msh"],
        [b("meshgen"), "plan.msh", "--strata", "strata.toml", "-q", "-o", "model.msh"],
        [b("submesh"), "model.msh", "--case", "case.toml", "--pool", "Pool X", "-q", "-o", "pool_x.msh"],
        [b("flow"), "pool_x.msh", "--case", "case.toml", "-q", "-o", "pool_x_dp.h5"],
        [b("faultinsert"), "model.msh", "--faults", "faults.geojson", "-q", "-o", "faulted.msh"],
        [b("solve"), "model.msh", "--case", "case.toml", "--pressure", "pool_x_dp.h5", "--solver", "cholmod",
         "--state", "none", "-q", "-o", "solve.h5"],
    ]
    for cmd in steps:
        r = subprocess.run(cmd, cwd=base, capture_output=True, text=True, timeout=600)
        if r.returncode != 0:
            raise SystemExit(f"FAIL: the valid chain breaks at {' '.join(cmd)} (exit {r.returncode}): {r.stderr.strip()}")
    flow = os.environ.get("OPM_FLOW") or shutil.which("flow")
    if not flow:
        raise SystemExit("FAIL: no OPM Flow (Debian libopm-simulators-bin; OPM_FLOW=path/to/flow) for ugs-import-eclipse's inputs")
    fixtures.write_eclipse(base, flow)


# ---- mutations ---------------------------------------------------------------------------------
def mutate(rng, path):
    """Mutates the file at `path` in place (or replaces it by a folder); returns a description."""
    with open(path, "rb") as fh:
        data = fh.read()
    text = path.endswith(TEXT_EXT)
    ops = ["flip", "truncate", "empty", "directory", "word"]
    if text:
        ops += ["number"] * 5 + ["delete_line"] * 2 + ["duplicate_line"]
    elif path.endswith(ECLIPSE_EXT):
        ops += ["flip"] * 2 + ["word"] * 2 + ["eclipse"] * 8
    else:
        ops += ["flip"] * 3 + ["word"] * 3
    op = rng.choice(ops)
    name = os.path.basename(path)
    if op == "eclipse":
        data, what = mutate_eclipse(rng, data)
        with open(path, "wb") as fh:
            fh.write(data)
        return f"{name}: {what}"
    if op == "directory":
        os.remove(path)
        os.mkdir(path)
        return f"{name}: a directory in its place"
    if op == "empty":
        data, what = b"", "emptied"
    elif op == "truncate":
        n = rng.randrange(len(data)) if data else 0
        data, what = data[:n], f"truncated to {n} bytes"
    elif op == "flip":
        b = bytearray(data)
        k = rng.choice([1, 1, 2, 4, 16])
        where = []
        for _ in range(k):
            if not b:
                break
            i = rng.randrange(len(b))
            b[i] ^= 1 << rng.randrange(8)
            where.append(i)
        data, what = bytes(b), f"bits flipped at bytes {where}"
    elif op == "word":
        b = bytearray(data)
        size = rng.choice([4, 8])
        i = rng.randrange(max(1, len(b) - size))
        b[i:i + size] = b"\xff" * size
        data, what = bytes(b), f"{size} bytes at {i} set to 0xff"
    elif op == "number":
        nums = list(NUMBER.finditer(data))
        if not nums:
            return mutate(rng, path)
        m = rng.choice(nums)
        rep = rng.choice(REPLACEMENTS)
        data = data[:m.start()] + rep + data[m.end():]
        line = data.count(b"\n", 0, m.start()) + 1
        what = f"line {line}: {m.group().decode(errors='replace')!r} -> {rep.decode()!r}"
    else:
        lines = data.split(b"\n")
        i = rng.randrange(len(lines))
        if op == "delete_line":
            what = f"line {i + 1} deleted ({lines[i][:40].decode(errors='replace')!r})"
            del lines[i]
        else:
            what = f"line {i + 1} duplicated"
            lines.insert(i, lines[i])
        data = b"\n".join(lines)
    with open(path, "wb") as fh:
        fh.write(data)
    return f"{name}: {what}"


def eclipse_headers(data):
    """Byte offsets of the array headers of an ECLIPSE binary file (Fortran records: a big-endian
    int32 length, the bytes, the length again; a header is a 16-byte record: name, count, type)."""
    heads, i = [], 0
    while i + 8 <= len(data):
        n = struct.unpack(">i", data[i:i + 4])[0]
        if n < 0 or i + 8 + n > len(data):
            break
        if n == 16:
            heads.append(i)
        i += 8 + n
    return heads


def mutate_eclipse(rng, data):
    """One change of an ECLIPSE binary file's structure: a header's item count, type or name (that of
    another array), or a data record's length marker."""
    b = bytearray(data)
    heads = eclipse_headers(data)
    h = rng.choice(heads)
    name = data[h + 4:h + 12].decode(errors="replace").strip()
    op = rng.choice(["count", "count", "type", "name", "marker", "marker"])
    if op == "count":
        old = struct.unpack(">i", data[h + 12:h + 16])[0]
        v = rng.choice([0, -1, 1, 2, 7, 66, 2**31 - 1, 2**30, -2**31, old - 1, old + 1, old + 1000])
        b[h + 12:h + 16] = struct.pack(">i", v)
        return bytes(b), f"array {name} at byte {h}: item count {old} -> {v}"
    if op == "type":
        t = rng.choice([b"INTE", b"REAL", b"DOUB", b"CHAR", b"LOGI", b"MESS", b"C000", b"C099", b"C0x1", b"X231", b"\xa0XYZ"])
        b[h + 16:h + 20] = t
        return bytes(b), f"array {name} at byte {h}: type -> {t!r}"
    if op == "name":
        other = rng.choice(heads)
        b[h + 4:h + 12] = data[other + 4:other + 12]
        return bytes(b), f"array {name} at byte {h}: renamed {data[other + 4:other + 12].decode(errors='replace').strip()}"
    m = h + 24
    if m + 4 > len(b):
        return bytes(b), "unchanged (no data record after the last header)"
    old = struct.unpack(">i", data[m:m + 4])[0]
    v = rng.choice([0, -4, 4, -2**31, 2**31 - 1, old - 4, old + 4, old * 2])
    b[m:m + 4] = struct.pack(">i", v)
    return bytes(b), f"array {name}: the data record marker at byte {m}: {old} -> {v}"


def prepare_run(base, specs, tool, seed, run_dir):
    """The run folder: in/ (links to the valid inputs, one of them mutated) and an empty out/."""
    shutil.rmtree(run_dir, ignore_errors=True)
    in_dir, out_dir = os.path.join(run_dir, "in"), os.path.join(run_dir, "out")
    os.makedirs(in_dir)
    os.makedirs(out_dir)
    for f in os.listdir(base):
        os.symlink(os.path.join(base, f), os.path.join(in_dir, f))
    if seed is None:
        return in_dir, out_dir, "unmutated"
    rng = random.Random(seed)
    target = rng.choice(specs[tool][1])
    p = os.path.join(in_dir, target)
    os.remove(p)
    shutil.copyfile(os.path.join(base, target), p)
    return in_dir, out_dir, mutate(rng, p)


# ---- checks ------------------------------------------------------------------------------------
def check_run(key, r, out_dir):
    """Problems of one finished run (empty list: fine)."""
    tool = tool_of(key)
    problems = []
    rc = r["rc"]
    if rc is None:
        return [f"no exit after {RUN_TIMEOUT} s (hang?)"]
    if rc < 0:
        problems.append(f"killed by signal {-rc}")
    elif rc not in (0, 1, 2):
        problems.append(f"exit code {rc} (expected 0, 1 or 2)")
    err_lines = [ln for ln in r["stderr"].splitlines() if ln.strip()]
    if rc == 2:
        if len(err_lines) != 1:
            problems.append(f"exit 2 with {len(err_lines)} lines on stderr (expected exactly one)")
        if not err_lines or not err_lines[0].startswith(f"ugs-{tool}: error: "):
            problems.append(f"exit 2 without an 'ugs-{tool}: error: ' line first")
    left = []
    for root, dirs, files in os.walk(out_dir):
        left += [os.path.relpath(os.path.join(root, x), out_dir) for x in dirs + files]
    if rc == 1 and tool == "calibrate":
        # A failed solver run is kept for diagnosis in the cache (failed-eval-*/, named in the error
        # line): the cache is a store that outlives runs, not an output. Refused input (exit 2) makes none.
        left = [x for x in left if x.split(os.sep)[0] != "calibration.cache"]
    if rc != 0 and left:
        problems.append(f"exit {rc} but the output folder holds {sorted(left)[:6]}")
    if rc == 0:
        texts = [("stdout", r["stdout"])]
        for rel in left:
            p = os.path.join(out_dir, rel)
            if os.path.isfile(p) and p.endswith(OUTPUT_TEXT_EXT):
                with open(p, errors="replace") as fh:
                    texts.append((rel, fh.read()))
        for name, t in texts:
            for ln_no, ln in enumerate(t.splitlines(), 1):
                if not ln.startswith("#") and NONFINITE.search(ln):
                    problems.append(f"exit 0 with a non-finite number in {name}:{ln_no}: {ln.strip()[:100]!r}")
                    break
    return problems


def run_one(build, base, specs, tool, seed, run_dir, keep=False):
    in_dir, out_dir, what = prepare_run(base, specs, tool, seed, run_dir)
    cmd = command(build, tool, specs[tool], in_dir, out_dir)
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=RUN_TIMEOUT,
                           cwd=run_dir, stdin=subprocess.DEVNULL)
        r = {"rc": p.returncode, "stdout": p.stdout, "stderr": p.stderr}
    except subprocess.TimeoutExpired as e:
        r = {"rc": None, "stdout": "", "stderr": str(e.stderr or "")}
    r.update(tool=tool, seed=seed, what=what, cmd=cmd, seconds=time.time() - t0,
             problems=check_run(tool, r, out_dir))
    if not keep:
        shutil.rmtree(run_dir, ignore_errors=True)
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build")
    ap.add_argument("work")
    ap.add_argument("--seed", type=int, default=2020)
    ap.add_argument("--runs", type=int, default=24, help="mutated runs of a tool of weight 1")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--tools", default="")
    ap.add_argument("--replay", default="", help="TOOL:SEED (TOOL as listed, e.g. solve:faulted): one run, kept in WORK/replay")
    a = ap.parse_args()
    build, work = os.path.abspath(a.build), os.path.abspath(a.work)
    specs = tool_specs()
    base = os.path.join(work, "base")
    os.environ.setdefault("GDAL_PAM_ENABLED", "NO")
    os.environ["OMPI_MCA_rmaps_base_oversubscribe"] = "1"

    if a.replay:
        tool, seed = a.replay.rsplit(":", 1)
        if not os.path.exists(os.path.join(base, "solve_top.h5")):
            make_chain(build, base)
        r = run_one(build, base, specs, tool, int(seed), os.path.join(work, "replay"), keep=True)
        print(f"mutation: {r['what']}\ncommand: {shlex.join(r['cmd'])}\nexit: {r['rc']}\nstderr:\n{r['stderr']}")
        print("problems: " + ("; ".join(r["problems"]) or "none"))
        return 1 if r["problems"] else 0

    t0 = time.time()
    shutil.rmtree(work, ignore_errors=True)
    make_chain(build, base)
    print(f"valid chain made in {time.time() - t0:.0f} s ({base})")
    tools = [t for t in (a.tools.split(",") if a.tools else specs) if t]
    jobs = []
    for ti, tool in enumerate(tools):
        jobs.append((tool, None))
        n = max(2, round(a.runs * specs[tool][0]))
        jobs += [(tool, a.seed * 100000 + ti * 1000 + k) for k in range(n)]
    results = []
    with cf.ThreadPoolExecutor(max_workers=a.jobs) as ex:
        futs = [ex.submit(run_one, build, base, specs, tool, seed,
                          os.path.join(work, "runs", f"{tool}-{seed if seed is not None else 'valid'}"))
                for tool, seed in jobs]
        for f in cf.as_completed(futs):
            results.append(f.result())

    failed = []
    print(f"{'tool':<14} {'runs':>5} {'exit0':>6} {'exit1':>6} {'exit2':>6} {'fail':>5} {'seconds':>8}")
    for tool in tools:
        rs = [r for r in results if r["tool"] == tool]
        codes = [r["rc"] for r in rs]
        bad = [r for r in rs if r["problems"]]
        print(f"{tool:<14} {len(rs):>5} {codes.count(0):>6} {codes.count(1):>6} {codes.count(2):>6} {len(bad):>5} "
              f"{sum(r['seconds'] for r in rs):>8.0f}")
        failed += sorted(bad, key=lambda r: (r["seed"] is not None, r["seed"] or 0))
    print(f"{len(results)} runs in {time.time() - t0:.0f} s")
    for r in failed:
        seed = "valid" if r["seed"] is None else r["seed"]
        print(f"FAIL ugs-{r['tool']} seed {seed}: {r['what']}: {'; '.join(r['problems'])}")
        err = r["stderr"].strip().splitlines()
        if err:
            print("     stderr: " + " | ".join(ln.strip() for ln in err[:3])[:300])
        if r["seed"] is not None:
            print(f"     replay: {sys.executable} {os.path.abspath(__file__)} {build} {work} --replay {r['tool']}:{seed}")
    if failed:
        print(f"FAIL: {len(failed)} of {len(results)} runs broke a rule")
        return 1
    print(f"ok: {len(results)} runs, every one exits 0/1/2 cleanly")
    return 0


if __name__ == "__main__":
    sys.exit(main())
