#!/usr/bin/python3
"""The linear solve against its peer (issue 43 item 4), from the logs bench/solve/run.sh wrote:

    compare_peers.py --ugs-log ugs.log --ugs-wall SECONDS --ugs-out ugs_linear.out \
                     --peer NAME=OUT_FILE=SECONDS [--peer ...]

The peer is the fastest of the FEniCSx configurations given. Targets: ugs-solve's whole run within
15 % of its own preconditioner setup plus solve, no more memory than the peer, fewer iterations
than the peer. Prints a table, the verdicts and `metric:` lines for bench/run-all.
"""
import argparse
import re
import sys


def number(pattern, text, what):
    m = re.search(pattern, text)
    if not m:
        sys.exit(f"compare_peers: {what} not found (pattern {pattern!r})")
    return float(m.group(1))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ugs-log", required=True)
    ap.add_argument("--ugs-wall", type=float, required=True)
    ap.add_argument("--ugs-out", required=True)
    ap.add_argument("--peer", action="append", required=True, help="NAME=OUT_FILE=WALL_SECONDS")
    a = ap.parse_args()

    log = open(a.ugs_log).read()
    iters = number(r"(\d+) linear iterations, \d+ preconditioner setups", log, "ugs-solve's linear iterations")
    setup = number(r"time: reading [0-9.]+ s, setup ([0-9.]+) s", log, "ugs-solve's setup time")
    solving = number(r"time: .*solving ([0-9.]+) s", log, "ugs-solve's solving time")
    rss = number(r"max RSS (\d+) kB", open(a.ugs_out).read(), "ugs-solve's max RSS") / 1024
    overhead = a.ugs_wall / (setup + solving) - 1

    peers = []
    for spec in a.peer:
        name, path, wall = spec.split("=")
        text = open(path).read()
        peers.append((name, float(wall), number(r"(\d+) CG iterations", text, f"{name}'s iterations"),
                      number(r"max RSS (\d+) kB", text, f"{name}'s max RSS") / 1024))
    best = min(peers, key=lambda p: p[1])

    print("| run | wall (s) | iterations | max RSS, largest process (MB) |")
    print("|---|---|---|---|")
    print(f"| ugs-solve (cg-hypre) | {a.ugs_wall:.1f} | {iters:.0f} | {rss:.0f} |")
    for name, wall, it, mb in peers:
        print(f"| FEniCSx, {name}{' (the peer)' if name == best[0] else ''} | {wall:.1f} | {it:.0f} | {mb:.0f} |")
    print(f"ugs-solve: whole run {a.ugs_wall:.1f} s against setup + solve {setup + solving:.1f} s: "
          f"{100 * overhead:+.1f} % (target <= 15 %): {'met' if overhead <= 0.15 else 'MISSED'}")
    print(f"memory: ugs-solve {rss:.0f} MB against the peer's {best[3]:.0f} MB (target: no more): "
          f"{'met' if rss <= best[3] else 'MISSED'}")
    print(f"iterations: ugs-solve {iters:.0f} against the peer's {best[2]:.0f} (target: fewer): "
          f"{'met' if iters < best[2] else 'MISSED'}")
    print(f"linear: peer ({best[0]}) / ugs-solve wall = {best[1] / a.ugs_wall:.2f}")
    print(f"metric: ugs-solve.linear.iterations {iters:.0f} 1")
    print(f"metric: ugs-solve.linear.overhead_vs_setup_solve {100 * overhead:.1f} %")
    for name, wall, it, _ in peers:
        print(f"metric: fenicsx_{name.lower()}.linear.iterations {it:.0f} 1")
    print(f"metric: solve.linear.peer_over_ugs {best[1] / a.ugs_wall:.2f} 1")
    print(f"metric: solve.linear.memory_ratio_to_peer {rss / best[3]:.2f} 1")


if __name__ == "__main__":
    main()
