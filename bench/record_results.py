#!/usr/bin/env python3
"""Bookkeeping of bench/run-all: merges the runs of some benchmarks into RESULTS.md and appends
their metrics to the history CSV.

    record_results.py RUNS_DIR RESULTS.md HISTORY.csv

RUNS_DIR holds one folder per benchmark run: `output` (what its run.sh printed) and `meta` (key=value
lines: date, commit, dirty, load_before, load_after, machine, settings, result, seconds). A run.sh reports a
key metric as a line `metric: NAME VALUE UNIT` (NAME without spaces, VALUE a number, UNIT one word;
`1` for ratios and counts); those lines become the section's metric table and one history row each.
RESULTS.md keeps the sections of benchmarks not in RUNS_DIR as they were: each section carries its
own date and commit. Both files are written whole to a temporary file and renamed.
"""
import csv
import io
import math
import os
import re
import sys
import tempfile

BEGIN = re.compile(r"^<!-- bench: (\S+) -->$")
HEADER = """# Benchmark results

Written by `bench/run-all` (do not edit by hand): each section is the latest run of one
`bench/<name>/run.sh`, with the date, the git commit it measured (dirty: the tree had uncommitted
changes), the machine and its load average before and after. `BENCH_ONLY=...` reruns some sections and
keeps the others with their own date and commit. Every run's metrics are also appended to
`{history}`, one row per metric, so that a regression shows.
"""
HISTORY_COLUMNS = ["date", "commit", "dirty", "load", "benchmark", "status", "metric", "value", "unit", "settings"]
METRIC = re.compile(r"^metric: (\S+) (\S+) (\S+)\s*$")


def fail(msg):
    print(f"record_results: error: {msg}", file=sys.stderr)
    sys.exit(2)


def read_meta(path):
    meta = {}
    with open(path) as fh:
        for line in fh:
            key, sep, value = line.rstrip("\n").partition("=")
            if sep:
                meta[key] = value
    for key in ("date", "commit", "dirty", "load_before", "machine", "result", "seconds"):
        if key not in meta:
            fail(f"{path}: no {key}= line (expected the meta file of a bench/run-all run)")
    return meta


def parse_output(name, text):
    """The output's lines without the metric lines, and the metrics (name, value text, unit)."""
    lines, metrics = [], []
    for number, line in enumerate(text.splitlines(), 1):
        if line.startswith("metric:"):
            m = METRIC.match(line)
            value = None
            if m:
                try:
                    value = float(m.group(2))
                except ValueError:
                    pass
            if value is None or not math.isfinite(value):
                print(f"record_results: warning: {name}/run.sh output line {number}: '{line}' is no "
                      "`metric: NAME VALUE UNIT` with a finite number; not recorded", file=sys.stderr)
                continue
            metrics.append((m.group(1), m.group(2), m.group(3)))
        else:
            lines.append(line)
    while lines and not lines[-1].strip():
        lines.pop()
    while lines and not lines[0].strip():
        lines.pop(0)
    return lines, metrics


def section(name, meta, lines, metrics):
    dirty = {"yes": " (dirty)", "no": "", "unknown": " (dirty: unknown)"}.get(meta["dirty"], "")
    out = [f"<!-- bench: {name} -->", f"## {name}", "",
           f"{meta['result']}, {meta['seconds']} s; {meta['date']}; commit {meta['commit']}{dirty}; "
           f"load {meta['load_before']} before, {meta.get('load_after', '?')} after; {meta['machine']}.", ""]
    if meta.get("settings"):
        out[-1:-1] = [f"Settings: `{meta['settings']}`."]
        out.insert(-1, "")
    if metrics:
        out += ["| metric | value | unit |", "|---|---|---|"]
        out += [f"| {m} | {v} | {u} |" for m, v, u in metrics]
        out.append("")
    if lines:
        out += lines
        out.append("")
    out.append(f"<!-- end bench: {name} -->")
    return "\n".join(out) + "\n"


def read_sections(path):
    """The sections of an earlier RESULTS.md, by benchmark name, as their text."""
    sections = {}
    if not os.path.exists(path):
        return sections
    name, buf = None, []
    with open(path) as fh:
        for number, line in enumerate(fh, 1):
            m = BEGIN.match(line.rstrip("\n"))
            if m:
                if name is not None:
                    fail(f"{path}:{number}: section {m.group(1)} starts inside section {name} (expected "
                         f"<!-- end bench: {name} --> first)")
                name, buf = m.group(1), [line]
            elif name is not None:
                buf.append(line)
                if line.rstrip("\n") == f"<!-- end bench: {name} -->":
                    sections[name] = "".join(buf)
                    name = None
    if name is not None:
        fail(f"{path}: section {name} has no end line (expected <!-- end bench: {name} -->)")
    return sections


def write_atomic(path, text, mode="w"):
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=os.path.basename(path) + ".tmp.", dir=folder)
    try:
        with os.fdopen(fd, mode) as fh:
            fh.write(text)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def main(argv):
    if len(argv) != 4:
        fail("usage: record_results.py RUNS_DIR RESULTS.md HISTORY.csv")
    runs, results, history = argv[1:]
    sections = read_sections(results)
    rows = []
    for name in sorted(os.listdir(runs)):
        run = os.path.join(runs, name)
        meta = read_meta(os.path.join(run, "meta"))
        with open(os.path.join(run, "output"), errors="replace") as fh:
            lines, metrics = parse_output(name, fh.read())
        sections[name] = section(name, meta, lines, metrics)
        status = "ok" if meta["result"] == "ok" else "failed"
        load = meta["load_before"].split()[0] if meta["load_before"].split() else ""
        rows += [[meta["date"], meta["commit"], meta["dirty"], load, name, status, m, v, u, meta.get("settings", "")]
                 for m, v, u in metrics]

    text = HEADER.format(history=os.path.relpath(history, os.path.dirname(os.path.abspath(results))))
    for name in sorted(sections):
        text += "\n" + sections[name]
    write_atomic(results, text)

    # The history is appended to: the old rows are kept as they are (checked against the header).
    old = ""
    if os.path.exists(history):
        with open(history, newline="") as fh:
            old = fh.read()
        first = old.splitlines()[0] if old else ""
        if old and first != ",".join(HISTORY_COLUMNS):
            fail(f"{history}:1: header '{first}' (expected {','.join(HISTORY_COLUMNS)})")
        if old and not old.endswith("\n"):
            old += "\n"
    if not old:
        old = ",".join(HISTORY_COLUMNS) + "\n"
    new = io.StringIO()
    csv.writer(new, lineterminator="\n").writerows(rows)
    write_atomic(history, old + new.getvalue())
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
