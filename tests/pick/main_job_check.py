#!/usr/bin/env python3
"""The README's main job (scripts/pick/main_job.sh) on a small bin: it must end with a
first pick that lies on a part of the bin, and write the picture.

Runs the job as scripts/run.sh does (our part, its templates, one synth bin, pick), then
checks that PICKS.json's first pick is within ADD 0.1 d of some part of the bin's ground
truth (BOP scene_gt.json, left camera, the same frame as pick's), with the mesh the job
wrote, and that pick.png is a PNG of the bin's size.
Usage: main_job_check.py FLEXSIGHT WORK_DIR SIZE
"""
import json
import os
import struct
import subprocess
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def stl_vertices(path):
    with open(path, "rb") as f:
        data = f.read()
    count = struct.unpack_from("<I", data, 80)[0]
    facets = np.frombuffer(data, dtype=np.dtype([("n", "<3f4"), ("v", "<9f4"), ("a", "<u2")]),
                           count=count, offset=84)
    return np.unique(facets["v"].reshape(-1, 3).astype(float), axis=0)


def add_distance(vertices, r_a, t_a, r_b, t_b):
    a = vertices @ np.asarray(r_a).reshape(3, 3).T + np.asarray(t_a)
    b = vertices @ np.asarray(r_b).reshape(3, 3).T + np.asarray(t_b)
    return float(np.linalg.norm(a - b, axis=1).mean())


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return struct.unpack(">II", head[16:24])


def main():
    flexsight, work, size = sys.argv[1:4]
    subprocess.run([os.path.join(REPO, "scripts/pick/main_job.sh"), "--out", work, "--size", size,
                    "--flexsight", flexsight, "--threads", "2"], check=True)
    with open(os.path.join(work, "PICKS.json")) as f:
        picks = json.load(f)
    first = picks.get("first_pick") if isinstance(picks.get("first_pick"), dict) else None
    first = first or picks["picks"][0]
    with open(os.path.join(work, "pick_job/bins/bin000/scene_gt.json")) as f:
        truth = json.load(f)["0"]
    vertices = stl_vertices(os.path.join(work, "pick_job/cad/obj_05.stl"))
    diameter = float(np.max(np.linalg.norm(vertices[:, None] - vertices[None], axis=2)))
    nearest = min(add_distance(vertices, first["R"], first["t_mm"], part["cam_R_m2c"], part["cam_t_m2c"])
                  for part in truth if part["obj_id"] == first["obj_id"])
    print(f"first pick: object {first['obj_id']}, ADD to the nearest part {nearest:.2f} mm "
          f"({nearest / diameter:.3f} d, {len(truth)} parts in the bin)")
    assert nearest < 0.1 * diameter, "the first pick lies on no part of the bin"
    width, height = (int(v) for v in size.split("x"))
    assert png_size(os.path.join(work, "pick.png")) == (width, height), "pick.png is not the bin's size"
    return 0


if __name__ == "__main__":
    sys.exit(main())
