#!/usr/bin/env python3
"""Compares two output folders of one Monte-Carlo bench (e.g. an unsharded run and a merge of
its shards): summary.json and every CSV file (trials.csv, frames.csv, flights.csv) must be equal
but for what each process measures for itself (wall and CPU times, cost, merged_from, the
section benches' and mononav's stage timings "timing", any key or column in milliseconds
"*_ms" / "*_ms_*", and ts2p's acceptance "met", which holds a CPU budget). Exit 0 when equal, 1
naming the first difference.

    compare_bench_outputs.py WHOLE_DIR MERGED_DIR
"""
import csv
import json
import sys
from pathlib import Path

MEASURED = {"wall_time_s", "cost", "merged_from", "timing"}


def measured(key):
    return key == "wall_time_s" or key.endswith("_ms") or "_ms_" in key


def without_measured(value):
    if isinstance(value, dict):
        return {k: without_measured(v) for k, v in value.items() if not measured(k)}
    if isinstance(value, list):
        return [without_measured(v) for v in value]
    return value


def figures(path):
    summary = json.loads(Path(path, "summary.json").read_text())
    for key in MEASURED:
        summary.pop(key, None)
    if summary.get("command") == "bench ts2p":
        summary.get("acceptance", {}).pop("met", None)
    return without_measured(summary)


def table(path):
    if not path.exists():
        return None
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    drop = {i for i, name in enumerate(rows[0]) if measured(name)} if rows else set()
    return [[c for i, c in enumerate(r) if i not in drop] for r in rows]


def first_difference(a, b, where=""):
    if type(a) is not type(b):
        return f"{where or '/'}: {a!r} vs {b!r}"
    if isinstance(a, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                return f"{where}/{key}: only in {'the first' if key in a else 'the second'}"
            found = first_difference(a[key], b[key], f"{where}/{key}")
            if found:
                return found
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{where}: {len(a)} vs {len(b)} entries"
        for i, (x, y) in enumerate(zip(a, b)):
            found = first_difference(x, y, f"{where}/{i}")
            if found:
                return found
        return None
    return None if a == b else f"{where or '/'}: {a!r} vs {b!r}"


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    whole, merged = sys.argv[1:]
    csv_names = sorted(p.name for p in Path(whole).glob("*.csv"))
    pairs = [("summary.json", figures(whole), figures(merged))]
    pairs += [(name, table(Path(whole, name)), table(Path(merged, name))) for name in csv_names]
    for name, a, b in pairs:
        difference = first_difference(a, b)
        if difference:
            print(f"compare: {name} differs at {difference}", file=sys.stderr)
            return 1
    trials = len(figures(whole).get("per_trial", []))
    print(f"compare: summary.json and {', '.join(csv_names) or 'no CSV'} equal ({trials} "
          "per-trial entries)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
