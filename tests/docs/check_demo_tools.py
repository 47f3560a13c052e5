#!/usr/bin/env python3
"""The target ugs-demo-tools (tools/CMakeLists.txt) builds exactly the tools `make demo` runs.

`make -n demo` of data-samples/po-plain prints the demo chain's commands without running them; each
tool appears as UGS_BIN/<tool>/<tool>. The set must equal the target's list at every scale: a tool
missing from the target would make a first `make demo` fail after minutes of building, a tool too
many would be compiled for nothing.
Run: check_demo_tools.py --makefile data-samples/po-plain/Makefile --tools ugs-mesh2d ugs-meshgen ...
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

FAILED = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        FAILED.append(what)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--makefile", required=True)
    ap.add_argument("--tools", nargs="+", required=True)
    args = ap.parse_args()
    target = set(args.tools)
    sample = os.path.dirname(os.path.abspath(args.makefile))
    with tempfile.TemporaryDirectory(prefix="ugs-demo-tools-") as out:
        for scale in ("demo", "tiny", "full"):
            r = subprocess.run(["make", "-n", "-C", sample, "demo", f"SCALE={scale}", "UGS_BIN=/UGSBIN",
                                f"OUT={out}/{scale}"], capture_output=True, text=True)
            check(r.returncode == 0, f"make -n demo SCALE={scale} exits 0 ({r.stderr.strip()[:200]})")
            used = set(re.findall(r"/UGSBIN/(ugs-[a-z0-9-]+)/\1\b", r.stdout))
            check(used == target, f"SCALE={scale}: the demo runs {', '.join(sorted(used))}; ugs-demo-tools "
                  f"builds {', '.join(sorted(target))}" + (f"; missing {', '.join(sorted(used - target))}"
                  if used - target else "") + (f"; not run {', '.join(sorted(target - used))}"
                  if target - used else ""))
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
