#!/usr/bin/env python3
"""flexsight serve under load on loopback, bounded in count and time.

One small simulated bin (synth bin 320x240, three T-LESS parts) and coarse templates of
every part are made here; the server is started with a small queue and body limit. Four
clients at once send good picks and malformed ones; then an oversized body, a client that
sends half a body and hangs up, one that sends a whole pick and hangs up before the answer.
After that the server still answers /health, and a good /pick answers what `flexsight pick
-o` writes for the same inputs and options (timing keys aside); every 200 answer of the
run is that same document. SIGTERM ends it with exit code 0.
"""
import argparse
import base64
import concurrent.futures
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time

import requests
from PIL import Image

# Options a request gives on top of the server's (pick's per-request options).
REQUEST_OPTIONS = {"stereo_downscale": 2, "depth_proposals": "on"}
CLI_OPTIONS = ["--stereo-downscale", "2", "--depth-proposals", "on"]


def run(cmd, **kw):
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=120, **kw)
    if result.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({result.returncode}): {result.stderr}")
    return result


def without_timings(value):
    """PICKS.json without its measured times: the 'seconds*' keys and the *_ms keys."""
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items()
                if not k.startswith("seconds") and not k.endswith("_ms")}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


class Check:
    def __init__(self):
        self.failures = []

    def __call__(self, condition, message):
        if not condition:
            self.failures.append(message)
            print("FAIL:", message, flush=True)


def start_server(flexsight, templates, cad, log_path):
    log = open(log_path, "w")
    server = subprocess.Popen([flexsight, "serve", "--templates", templates, "--cad", cad, "--port", "0",
                               "--queue", "2", "--timeout-ms", "60000", "--max-body", "1M", "--threads", "2"],
                              stdout=subprocess.PIPE, stderr=log, text=True)
    ready = server.stdout.readline()  # "serve: listening on http://127.0.0.1:PORT (...)"
    if "listening on http://127.0.0.1:" not in ready:
        server.kill()
        sys.exit(f"serve did not start: {ready!r}, stderr: {open(log_path).read()}")
    port = int(ready.split("127.0.0.1:")[1].split()[0])
    lines = []
    reader = threading.Thread(target=lambda: lines.extend(server.stdout), daemon=True)
    reader.start()
    return server, port, lines, reader


def half_body_then_hang_up(port):
    with socket.create_connection(("127.0.0.1", port), timeout=10) as s:
        s.sendall(b"POST /pick HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
                  b"Content-Length: 1000\r\n\r\n{\"left\": \"")


def whole_pick_then_hang_up(port, body):
    data = json.dumps(body).encode()
    with socket.create_connection(("127.0.0.1", port), timeout=10) as s:
        s.sendall(b"POST /pick HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n" +
                  f"Content-Length: {len(data)}\r\n\r\n".encode() + data)
        time.sleep(0.2)  # the request is read, the pick queued; the answer finds no one


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--flexsight", required=True)
    parser.add_argument("--cad", required=True)
    args = parser.parse_args()
    check = Check()
    started = time.time()
    work = tempfile.mkdtemp(prefix="serve_load_")
    try:
        # Bad options: one line naming the option, exit 1, before anything loads.
        for bad, named in ((["--port", "http"], "option --port"), (["--queue", "0"], "option --queue"),
                           (["--max-body", "1X"], "option --max-body"), (["--colour", "red"], "option --colour"),
                           (["--templates", os.path.join(work, "none.tpl")], "none.tpl")):
            argv = [args.flexsight, "serve"] + (bad if bad[0] == "--templates" else ["--templates", "t.tpl"] + bad)
            r = subprocess.run(argv, capture_output=True, text=True, timeout=60)
            lines = r.stderr.strip().splitlines()
            check(r.returncode == 1 and len(lines) == 1 and named in lines[0] and not r.stdout,
                  f"serve {' '.join(bad)}: exit {r.returncode}, {r.stderr!r}")
        templates = os.path.join(work, "parts.tpl")
        run([args.flexsight, "pose-templates", args.cad, "--views", "8", "--threads", "2", "-o", templates])
        run([args.flexsight, "synth", "bin", "--count", "1", "--seed", "5", "--size", "320x240", "--parts", "3..3",
             "--cad", args.cad, "-o", os.path.join(work, "bins")])
        bin_dir = os.path.join(work, "bins", "bin000")
        left, right, calib = (os.path.join(bin_dir, f) for f in ("im0.png", "im1.png", "calib.txt"))
        small = os.path.join(work, "small.png")
        Image.open(right).resize((160, 120)).save(small)
        wide_calib = os.path.join(bin_dir, "wide_calib.txt")  # beside the projector pattern calib.txt names
        with open(calib) as f, open(wide_calib, "w") as out:
            out.write(f.read().replace("width=320", "width=400"))
        cli_json = os.path.join(work, "cli.json")
        run([args.flexsight, "pick", left, right, "--calib", calib, "--templates", templates, "--cad", args.cad,
             "--threads", "2", "--quiet", "-o", cli_json] + CLI_OPTIONS)
        expected = without_timings(json.load(open(cli_json)))
        check(len(expected["picks"]) > 0, "the CLI's pick found parts to compare")

        server, port, lines, reader = start_server(args.flexsight, templates, args.cad, os.path.join(work, "serve.err"))
        url = f"http://127.0.0.1:{port}"
        good = dict(left=left, right=right, calib=calib, **REQUEST_OPTIONS)
        malformed = [
            ("not json", "body: not JSON"),
            ({"right": right, "calib": calib}, "key left: missing"),
            (dict(good, colour="red"), "option --colour: unknown option"),
            (dict(good, left=os.path.join(work, "none.png")), "none.png"),
            (dict(good, right=small), "small.png: is 160x120 but the left image"),
            (dict(good, calib=wide_calib), "wide_calib.txt: is for 400x240 images, not 320x240"),
            (dict(good, parts="99"), "option --parts"),
            (dict(good, tile="huge"), "option --tile: expected a whole number"),
            (dict(good, templates="other.tpl"), "key templates: loaded once"),
            (dict(good, score=0.5), "option --score"),
        ]
        answers = []  # (status, json or None)

        def send(body):
            data = body if isinstance(body, str) else json.dumps(body)
            r = requests.post(url + "/pick", data=data, timeout=120)
            answers.append((r.status_code, r.json(), r.headers.get("Retry-After")))
            return r

        def client(index):
            jobs = [good] + [m for i, m in enumerate(malformed) if i % 4 == index]
            for body in jobs:
                if body is good:
                    r = send(good)
                    check(r.status_code in (200, 503), f"client {index}: good pick answered {r.status_code}")
                    if r.status_code == 503:
                        check(r.headers.get("Retry-After") is not None, "503 without Retry-After")
                else:
                    payload, message = body
                    r = send(payload)
                    check(r.status_code == 400, f"{message}: status {r.status_code}")
                    check(message in r.json().get("error", ""), f"{message!r} not in {r.json()}")

        with concurrent.futures.ThreadPoolExecutor(4) as pool:
            list(pool.map(client, range(4)))

        big = json.dumps(dict(good, left_png=base64.b64encode(os.urandom(800_000)).decode()))
        r = requests.post(url + "/pick", data=big, timeout=60)
        check(r.status_code == 413 and "--max-body" in r.json()["error"], f"oversized body: {r.status_code} {r.text}")
        half_body_then_hang_up(port)
        whole_pick_then_hang_up(port, good)

        # A second server on the same port is refused (no port sharing), after loading.
        r2 = subprocess.run([args.flexsight, "serve", "--templates", templates, "--cad", args.cad, "--port", str(port)],
                            capture_output=True, text=True, timeout=120)
        check(r2.returncode == 1 and "option --port: cannot listen" in r2.stderr, f"second serve: {r2.stderr!r}")
        r = requests.get(url + "/pick", timeout=10)
        check(r.status_code == 404 and "GET /pick: not found" in r.json()["error"], f"GET /pick: {r.status_code} {r.text}")
        with open(left, "rb") as f:
            cut = base64.b64encode(f.read()[:80]).decode()
        cut_body = {k: v for k, v in good.items() if k != "left"}
        cut_body["left_png"] = cut
        r = requests.post(url + "/pick", json=cut_body, timeout=30)
        check(r.status_code == 400 and r.json()["error"].startswith("body:left_png: "), f"a cut PNG: {r.text}")
        health = requests.get(url + "/health", timeout=10)
        check(health.status_code == 200 and health.json()["status"] == "ok" and health.json()["models_loaded"],
              f"/health after the load: {health.status_code} {health.text}")
        r = send(good)
        check(r.status_code == 200, f"the good pick after the load: {r.status_code} {r.text[:200]}")
        # The same pick with its images in the body.
        with open(left, "rb") as fl, open(right, "rb") as fr:
            inline = dict(calib=calib, left_png=base64.b64encode(fl.read()).decode(),
                          right_png=base64.b64encode(fr.read()).decode(), **REQUEST_OPTIONS)
        r_inline = requests.post(url + "/pick", json=inline, timeout=120)
        check(r_inline.status_code == 200, f"images in the body: {r_inline.status_code} {r_inline.text[:200]}")
        if r_inline.status_code == 200:
            got = without_timings(r_inline.json())
            check(got["inputs"]["left"] == "body:left_png", f"inline inputs named {got['inputs']}")
            got["inputs"] = expected["inputs"]
            check(got == expected, "images in the body: another answer than the CLI's")

        ok = [a for a in answers if a[0] == 200]
        check(len(ok) >= 2, f"{len(ok)} good picks answered 200")
        for status, body, _ in ok:
            check(without_timings(body) == expected, "a 200 answer differs from flexsight pick -o")

        metrics = requests.get(url + "/metrics", timeout=10).json()
        # At least: the half body that was hung up on may be counted as a 400 too.
        check(metrics["answers"].get("400", 0) >= len(malformed) + 1, f"/metrics 400s: {metrics['answers']}")
        check(metrics["answers"].get("404", 0) == 1, f"/metrics 404s: {metrics['answers']}")
        check(metrics["answers"].get("413", 0) == 1, f"/metrics 413s: {metrics['answers']}")
        check(metrics["requests"] >= len(answers) + 2, f"/metrics requests {metrics['requests']}")
        for series in ("total", "queue_wait", "stereo", "detection", "pose"):
            s = metrics["seconds"].get(series)
            check(s is not None and 0 <= s["p50"] <= s["p90"] <= s["p99"] <= s["max"], f"/metrics {series}: {s}")

        server.send_signal(signal.SIGTERM)
        try:
            code = server.wait(timeout=60)
        except subprocess.TimeoutExpired:
            server.kill()
            code = "no exit within 60 s"
        reader.join(timeout=5)
        check(code == 0, f"exit after SIGTERM: {code}, stderr: {open(os.path.join(work, 'serve.err')).read()[-500:]}")
        check(any("serve: stopped" in line for line in lines), "no 'serve: stopped' line")
        print(f"{len(answers)} answers ({len(ok)} picks), {time.time() - started:.1f} s", flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if check.failures:
        sys.exit(f"{len(check.failures)} checks failed")


if __name__ == "__main__":
    main()
