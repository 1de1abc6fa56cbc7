#!/usr/bin/env python3
"""SHA-256 of every file under a folder, with what legitimately changes between runs
taken out first: the timings and the paths. JSON files are hashed after dropping keys
that hold a time (seconds, milliseconds, wall time, rates), with the run's own folder
and the checkout's folder (the binary's default data paths name it) written as
placeholders, so that two checkouts of one commit give the same sums;
CSV files after dropping a `time` column; Markdown reports are skipped (they are made
from the JSON, with the timings in prose). Images and binary files are hashed as they are.

usage: normalised_sums.py FOLDER  (run in the checkout; prints "sum  relative/path" lines, sorted)
"""
import csv
import hashlib
import io
import json
import pathlib
import re
import sys

TIMING_KEY = re.compile(r"(second|_ms$|^ms_|_ms_|wall|per_second|images_per|time|latency)", re.I)


def without_timings(value, root, checkout):
    if isinstance(value, dict):
        return {k: without_timings(v, root, checkout) for k, v in value.items()
                if not TIMING_KEY.search(k)}
    if isinstance(value, list):
        return [without_timings(v, root, checkout) for v in value]
    if isinstance(value, str):
        return value.replace(root, "<run>").replace(checkout, "<checkout>")
    return value


def normalised_bytes(path, root, checkout):
    if path.suffix == ".json":
        data = json.loads(path.read_text())
        return json.dumps(without_timings(data, root, checkout), sort_keys=True).encode()
    if path.suffix == ".csv":
        rows = list(csv.reader(io.StringIO(path.read_text())))
        keep = [i for i, name in enumerate(rows[0]) if name.strip() != "time"] if rows else []
        return "\n".join(",".join(row[i] for i in keep) for row in rows).encode()
    return path.read_bytes()


def main():
    folder = pathlib.Path(sys.argv[1])
    root = str(folder.resolve())
    checkout = str(pathlib.Path.cwd().resolve())
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        if path.suffix == ".md":
            continue
        digest = hashlib.sha256(normalised_bytes(path, root, checkout)).hexdigest()
        print(f"{digest}  {path.relative_to(folder)}")


if __name__ == "__main__":
    main()
