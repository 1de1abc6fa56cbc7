#!/usr/bin/env python3
"""Latency and throughput of a running `flexsight serve` (docs/serve.md, "Benchmark").

N requests from C concurrent clients, M of them malformed (spread evenly); prints a
Markdown table of latency percentiles per kind of answer, the throughput, the answers by
status, the server's own /metrics percentiles per pick stage, and whether every good
answer was the same document (timings aside).

  scripts/service/serve_bench.py --url http://127.0.0.1:8080 --left L --right R --calib C \
      --requests 200 --clients 4 --malformed 20 [--option stereo_downscale=2 ...]
"""
import argparse
import concurrent.futures
import json
import math
import time

import requests


def percentile(samples, q):
    """Nearest rank, as /metrics computes it."""
    if not samples:
        return float("nan")
    ordered = sorted(samples)
    return ordered[max(1, math.ceil(q * len(ordered) - 1e-9)) - 1]


def without_timings(value):
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k != "seconds" and not k.endswith("_ms")}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def option_value(text):
    try:
        return json.loads(text)
    except json.JSONDecodeError:
        return text


MALFORMED = [
    lambda good: "{not json",
    lambda good: {k: v for k, v in good.items() if k != "left"},
    lambda good: dict(good, left=good["left"] + ".missing.png"),
    lambda good: dict(good, colour="red"),
    lambda good: dict(good, tile="huge"),
]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--url", required=True)
    parser.add_argument("--left", required=True)
    parser.add_argument("--right", required=True)
    parser.add_argument("--calib", required=True)
    parser.add_argument("--option", action="append", default=[], help="KEY=VALUE, a pick option of each request")
    parser.add_argument("--requests", type=int, default=200)
    parser.add_argument("--clients", type=int, default=4)
    parser.add_argument("--malformed", type=int, default=20)
    parser.add_argument("--expected", help="a PICKS.json (pick -o) every good answer must equal, timings aside")
    args = parser.parse_args()

    good = {"left": args.left, "right": args.right, "calib": args.calib}
    for item in args.option:
        key, _, value = item.partition("=")
        good[key] = option_value(value)
    every = max(1, args.requests // max(1, args.malformed)) if args.malformed else 0
    bodies = []
    for i in range(args.requests):
        bad = every and i % every == every - 1 and sum(1 for b in bodies if b[0] == "malformed") < args.malformed
        bodies.append(("malformed", MALFORMED[i % len(MALFORMED)](good)) if bad else ("pick", good))

    def send(item):
        kind, body = item
        data = body if isinstance(body, str) else json.dumps(body)
        start = time.perf_counter()
        r = requests.post(args.url + "/pick", data=data, timeout=600)
        return kind, r.status_code, time.perf_counter() - start, r.text

    started = time.perf_counter()
    with concurrent.futures.ThreadPoolExecutor(args.clients) as pool:
        results = list(pool.map(send, bodies))
    wall = time.perf_counter() - started

    expected = without_timings(json.load(open(args.expected))) if args.expected else None
    good_docs = [without_timings(json.loads(text)) for kind, status, _, text in results if status == 200]
    same = all(d == good_docs[0] for d in good_docs) if good_docs else False
    same_as_cli = all(d == expected for d in good_docs) if expected is not None and good_docs else None

    print(f"{args.requests} requests, {args.clients} clients, {args.malformed} malformed, {wall:.1f} s\n")
    print("| answers | count | p50 s | p90 s | p99 s | max s |\n|---|---|---|---|---|---|")
    for label, keep in (("pick 200", lambda k, s: k == "pick" and s == 200),
                        ("malformed 4xx", lambda k, s: k == "malformed" and 400 <= s < 500),
                        ("other", lambda k, s: not ((k == "pick" and s == 200) or (k == "malformed" and 400 <= s < 500)))):
        lat = [t for k, s, t, _ in results if keep(k, s)]
        if lat:
            print(f"| {label} | {len(lat)} | {percentile(lat, .5):.3f} | {percentile(lat, .9):.3f} | "
                  f"{percentile(lat, .99):.3f} | {max(lat):.3f} |")
    statuses = {}
    for _, s, _, _ in results:
        statuses[s] = statuses.get(s, 0) + 1
    picks = sum(1 for k, s, _, _ in results if k == "pick" and s == 200)
    print(f"\nthroughput: {picks / wall:.3f} picks/s ({len(results) / wall:.3f} requests/s); answers by status: "
          f"{dict(sorted(statuses.items()))}; good answers all the same document: {same}"
          + ("" if same_as_cli is None else f"; equal to pick -o's: {same_as_cli}"))
    metrics = requests.get(args.url + "/metrics", timeout=30).json()
    print("\nserver /metrics (since it started):\n\n| series | count | p50 s | p90 s | p99 s | max s |\n|---|---|---|---|---|---|")
    for name, s in metrics["seconds"].items():
        print(f"| {name} | {s['count']} | {s['p50']:.3f} | {s['p90']:.3f} | {s['p99']:.3f} | {s['max']:.3f} |")


if __name__ == "__main__":
    main()
