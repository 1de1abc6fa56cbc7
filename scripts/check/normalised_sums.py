#!/usr/bin/env python3
"""SHA-256 of every file under a folder, with what legitimately changes between runs
taken out first: the timings. JSON files are hashed after dropping keys that hold a
time (seconds, milliseconds, wall time, rates) and the paths of the run's own folder;
CSV files after dropping a `time` column; Markdown reports are skipped (they are made
from the JSON, with the timings in prose). Images and binary files are hashed as they are.

usage: normalised_sums.py FOLDER  (prints "sum  relative/path" lines, sorted)
"""
import csv
import hashlib
import io
import json
import pathlib
import re
import sys

TIMING_KEY = re.compile(r"(second|_ms$|^ms_|_ms_|wall|per_second|images_per|time|latency)", re.I)


def without_timings(value, root):
    if isinstance(value, dict):
        return {k: without_timings(v, root) for k, v in value.items() if not TIMING_KEY.search(k)}
    if isinstance(value, list):
        return [without_timings(v, root) for v in value]
    if isinstance(value, str):
        return value.replace(root, "<run>")
    return value


def normalised_bytes(path, root):
    if path.suffix == ".json":
        data = json.loads(path.read_text())
        return json.dumps(without_timings(data, root), sort_keys=True).encode()
    if path.suffix == ".csv":
        rows = list(csv.reader(io.StringIO(path.read_text())))
        keep = [i for i, name in enumerate(rows[0]) if name.strip() != "time"] if rows else []
        return "\n".join(",".join(row[i] for i in keep) for row in rows).encode()
    return path.read_bytes()


def main():
    folder = pathlib.Path(sys.argv[1])
    root = str(folder.resolve())
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        if path.suffix == ".md":
            continue
        digest = hashlib.sha256(normalised_bytes(path, root)).hexdigest()
        print(f"{digest}  {path.relative_to(folder)}")


if __name__ == "__main__":
    main()
