#!/usr/bin/python3
"""Stage table of bench/study/run.sh: the recipe lines timed by timed-shell grouped into the study's
stages, the whole study's wall time, CPU and peak memory, and its ratio to one linear solve."""
import argparse
import re

STAGES = [  # (stage, regex on the command line), first match wins
    ("plans, meshes, faults", r"ugs-mesh2d|ugs-meshgen|ugs-meshinfo|ugs-faultinsert|fault_refinement"),
    ("flow sub-meshes and pressures", r"ugs-submesh|ugs-flow"),
    ("faulted model (safe scale, stress history)", r"ugs-solve \S*faulted\.msh"),
    ("calibration", r"ugs-calibrate"),
    ("continuous 1950-1964 (production)", r"ugs-solve .*--until 1964-04-01"),
    ("continuous 1964-2033", r"ugs-solve .*--restart"),
    ("sampling at the PS points", r"ugs-sample"),
    ("seismicity forecast", r"ugs-seismicity"),
    ("ensemble", r"ugs-ensemble"),
    ("report", r"ugs-report"),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("times")
    ap.add_argument("--study-wall", type=float, required=True)
    ap.add_argument("--rss-peak-kB", type=float, default=0)
    ap.add_argument("--linear-wall", type=float, required=True)
    ap.add_argument("--linear-rss-kB", type=float, required=True)
    ap.add_argument("--linear-log", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--scale", default="full")
    a = ap.parse_args()
    rows = {}
    for line in open(a.times):
        start, wall, cpu, rss, cmd = line.rstrip("\n").split("\t", 4)
        stage = next((s for s, rx in STAGES if re.search(rx, cmd)), None)
        if stage is None:
            continue  # mkdir, sed, grep of the logs
        r = rows.setdefault(stage, {"n": 0, "wall": 0.0, "cpu": 0.0, "rss": 0.0, "first": float(start), "last": 0.0})
        r["n"] += 1
        r["wall"] += float(wall)
        r["cpu"] += float(cpu)
        r["rss"] = max(r["rss"], float(rss))
        r["first"] = min(r["first"], float(start))
        r["last"] = max(r["last"], float(start) + float(wall))
    t0 = min(r["first"] for r in rows.values())
    lin_log = open(a.linear_log).read()
    m = re.search(r"time: reading ([0-9.]+) s, setup ([0-9.]+) s, solving ([0-9.]+) s", lin_log)
    it = re.search(r"(\d+) linear iterations", lin_log)
    nodes = re.search(r"(\d+) nodes", lin_log)
    out = ["| stage | commands | from [min] | to [min] | wall [s] | CPU [s] | peak RSS [MB] |", "|---|---|---|---|---|---|---|"]
    for stage, _ in STAGES:
        if stage in rows:
            r = rows[stage]
            out.append(f"| {stage} | {r['n']} | {(r['first'] - t0) / 60:.1f} | {(r['last'] - t0) / 60:.1f} | {r['wall']:.0f} | "
                       f"{r['cpu']:.0f} | {r['rss'] / 1024:.0f} |")
    cpu = sum(r["cpu"] for r in rows.values())
    ratio = a.study_wall / a.linear_wall
    out += ["",
            f"study (make demo SCALE={a.scale}): wall {a.study_wall:.0f} s ({a.study_wall / 60:.1f} min; target 60 min), CPU {cpu:.0f} s, "
            f"peak resident memory of all its processes {a.rss_peak_kB / 1048576:.2f} GB (target 16 GB)",
            f"one linear elastic solve of the same mesh ({nodes.group(1) if nodes else '?'} nodes, one process): wall "
            f"{a.linear_wall:.1f} s" + (f" (reading {m.group(1)} s, setup {m.group(2)} s, solving {m.group(3)} s, "
                                          f"{it.group(1) if it else '?'} CG iterations)" if m else "") +
            f", {a.linear_rss_kB / 1024:.0f} MB",
            f"ratio study / linear solve: {ratio:.0f} (target at most 150)",
            f"metric: study.wall {a.study_wall:.0f} s",
            f"metric: study.cpu {cpu:.0f} s",
            f"metric: study.rss_total {a.rss_peak_kB / 1048576:.2f} GB",
            f"metric: study.linear_solve.wall {a.linear_wall:.1f} s",
            f"metric: study.ratio_to_linear_solve {ratio:.1f} 1"]
    text = "\n".join(out)
    print(text)
    open(f"{a.out}/summary.md", "w").write(text + "\n")


if __name__ == "__main__":
    main()
