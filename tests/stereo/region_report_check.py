#!/usr/bin/python3
"""scripts/stereo/region_report.py on a 320x240 bin that `flexsight synth bin` writes here:
the regions partition the pixels with ground truth, a run of the matcher scores as
`flexsight eval` does, the ground truth scores 0 everywhere, a result wrong only on the
parts is bad there only, a result off by 5 px is bad everywhere, the Markdown section
replaces only the text between its markers, and bad input writes nothing.

usage: region_report_check.py FLEXSIGHT WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "..", "scripts", "stereo")
sys.path.insert(0, SCRIPTS)
from pfm_io import read_pfm, write_pfm  # noqa: E402
from region_report import REGIONS, regions  # noqa: E402

REPORT = os.path.join(SCRIPTS, "region_report.py")


def run(*arguments, expect=0):
    done = subprocess.run([sys.executable, REPORT, *arguments], capture_output=True, text=True)
    if done.returncode != expect:
        sys.exit(f"FAIL: exit {done.returncode}, expected {expect}: {arguments}\n{done.stderr}")
    return done


def figures(out):
    with open(os.path.join(out, "regions.json")) as f:
        return json.load(f)[0]["scenes"]["bin000"]


def check(condition, message):
    if not condition:
        sys.exit("FAIL: " + message)


def main():
    flexsight, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    bins = os.path.join(work, "bins")
    subprocess.run([flexsight, "synth", "bin", "--size", "320x240", "--count", "1",
                    "--seed", "3", "-o", bins], check=True, stdout=subprocess.DEVNULL)
    scene = os.path.join(bins, "bin000")

    doc = os.path.join(work, "doc.md")
    with open(doc, "w") as f:
        f.write("# before\n<!-- region_report:begin -->\nold\n"
                "<!-- region_report:end -->\n# after\n")
    matched = os.path.join(work, "matched")
    run(bins, "--out", matched, "--flexsight", flexsight, "--images",
        os.path.join(work, "images"), "--markdown", doc)
    got = figures(matched)
    shares = sum(got[name]["share"] for name in REGIONS)
    check(abs(shares - 1.0) < 1e-9, f"the regions' shares sum to {shares}")
    for name in REGIONS:
        check(got[name]["share"] > 0.001, f"region {name} holds {got[name]['share']}")
    with open(os.path.join(matched, "bins", "report.json")) as f:
        evaluated = json.load(f)["scenes"][0]["all"]["bad_2"]
    check(abs(got["all"]["bad2"] - evaluated) < 1e-3,
          f"bad-2 all {got['all']['bad2']} against flexsight eval's {evaluated}")
    check(got["all"]["bad2"] < 30 and got["parts, left only"]["bad2"] > got["floor"]["bad2"],
          f"the matcher's figures {got}")
    with open(doc) as f:
        text = f.read()
    check(text.startswith("# before\n<!-- region_report:begin -->") and
          text.endswith("<!-- region_report:end -->\n# after\n") and "old" not in text and
          "| bin000 |" in text and "](images/regions_bins.png)" in text,
          "the Markdown section:\n" + text)
    check(os.path.getsize(os.path.join(work, "images", "regions_bins.png")) > 1000, "no picture")

    gt = read_pfm(os.path.join(scene, "disp0GT.pfm"))
    _, masks = regions(scene)
    parts = masks["parts, both cameras"] | masks["parts, left only"]
    results = {"truth": gt, "off": gt + 5.0, "parts_wrong": np.where(parts, gt + 3.0, gt)}
    for label, disp in results.items():
        os.makedirs(os.path.join(work, label), exist_ok=True)
        write_pfm(os.path.join(work, label, "bin000_disp.pfm"), disp)
        run(f"{bins}={os.path.join(work, label)}", "--out", os.path.join(work, label + "_out"))
    truth, off, parts_wrong = (figures(os.path.join(work, k + "_out")) for k in results)
    for name in ("all", "parts") + REGIONS:
        check(truth[name]["bad2"] == 0, f"the ground truth scores {truth[name]} on {name}")
        check(off[name]["bad2"] == 100, f"a 5-px offset scores {off[name]} on {name}")
    for name in ("parts", "parts, both cameras", "parts, left only"):
        check(parts_wrong[name]["bad2"] == 100, f"wrong parts score {parts_wrong[name]} on {name}")
    for name in ("walls", "floor", "outside the field"):
        check(parts_wrong[name]["bad2"] == 0, f"wrong parts score {parts_wrong[name]} on {name}")
    check(abs(parts_wrong["all"]["bad2"] - 100 * parts_wrong["parts"]["share"]) < 1e-6,
          "bad-2 all is not the parts' share when only the parts are wrong")

    # Bad input: one line naming the problem, exit 1, nothing written.
    empty = os.path.join(work, "empty")
    os.makedirs(empty)
    plain = os.path.join(work, "plain.md")
    with open(plain, "w") as f:
        f.write("# a page without the markers\n")
    for arguments, words in (
            ([f"{bins}={empty}", "--out", os.path.join(work, "x1")],
             "bin000_disp.pfm: no such file"),
            ([empty, "--out", os.path.join(work, "x2")], "no scene folder"),
            ([scene, "--out", os.path.join(work, "x3")], "a scene, not a set"),
            ([bins, "--out", os.path.join(work, "x4"), "--flexsight", os.path.join(work, "none")],
             "no such executable"),
            ([f"{bins}={os.path.join(work, 'truth')}", "--out", os.path.join(work, "x5"),
              "--markdown", plain], "does not hold")):
        done = run(*arguments, expect=1)
        check(words in done.stderr and done.stderr.count("\n") == 1, f"message {done.stderr!r}")
        check(not os.path.exists(arguments[arguments.index("--out") + 1]), f"{arguments} wrote")
    print("region_report: all checks passed")


if __name__ == "__main__":
    main()
