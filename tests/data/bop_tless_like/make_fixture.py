#!/usr/bin/env python3
"""Writes a tiny scene in the layout of T-LESS as the BOP toolkit distributes it
(test_primesense/000001/...), for tests/dataset/test_bop_tless_fixture.cpp.

Everything that the real files have is kept: scene_camera.json with T-LESS's extra keys
(cam_R_w2c, cam_t_w2c, elev, mode), depth_scale 0.1, 16-bit depth PNGs, PNG rgb,
scene_gt_info.json with the BOP toolkit's boxes (width = x_max - x_min), mask_visib/
only (no mask/), and the JSON laid out as the toolkit's save_json writes it. Images are
32x24 instead of 720x540 so the fixture stays a few KB; image 1 is stored gray, which
the readers must tolerate. Run from this folder: python3 make_fixture.py
"""
import json
import os

import numpy as np
from PIL import Image

W, H = 32, 24
SCENE = "000001"
K = [1075.65091572, 0.0, 374.06888344, 0.0, 1073.90347929, 255.72159802, 0.0, 0.0, 1.0]


def save_json(path, content):
    # The BOP toolkit's inout.save_json: one line per image, keys sorted.
    with open(path, "w") as f:
        f.write("{\n")
        items = sorted(content.items(), key=lambda x: x[0])
        for i, (k, v) in enumerate(items):
            f.write('  "{}": {}'.format(k, json.dumps(v, sort_keys=True)))
            f.write(",\n" if i != len(items) - 1 else "\n")
        f.write("}")


def bop_box(mask):
    ys, xs = mask.nonzero()
    if len(xs) == 0:
        return [-1, -1, -1, -1]
    return [int(xs.min()), int(ys.min()), int(xs.max() - xs.min()), int(ys.max() - ys.min())]


def main():
    for sub in ("rgb", "depth", "mask_visib"):
        os.makedirs(os.path.join(SCENE, sub), exist_ok=True)
    # Two parts per image: a rectangle in front, a larger one partly behind it.
    rects = {0: [(2, (3, 4, 10, 8), 6000), (25, (9, 7, 14, 12), 7000)],
             1: [(5, (20, 10, 8, 6), 6500)]}
    cams, gts, infos = {}, {}, {}
    for im_id, parts in rects.items():
        depth = np.full((H, W), 9000, np.uint16)
        owner = np.full((H, W), -1)
        zbuf = np.full((H, W), 1 << 30)
        for k, (_, (x, y, w, h), z) in enumerate(parts):
            region = np.zeros((H, W), bool)
            region[y:y + h, x:x + w] = True
            closer = region & (z < zbuf)
            zbuf[closer] = z
            owner[closer] = k
            depth[closer] = z
        depth[0, :4] = 0  # a sensor hole
        Image.fromarray(depth).save(os.path.join(SCENE, "depth", "%06d.png" % im_id))
        xs, ys = np.meshgrid(np.arange(W), np.arange(H))
        rgb = np.stack([xs * 7, ys * 9, (xs + ys) * 3], axis=2).astype(np.uint8)
        image = Image.fromarray(rgb)
        if im_id == 1:
            image = image.convert("L")
        image.save(os.path.join(SCENE, "rgb", "%06d.png" % im_id))
        cams[im_id] = {"cam_K": K, "cam_R_w2c": [1.0, 0.0, 0.0, 0.0, -0.5, -0.866025, 0.0,
                                                  0.866025, -0.5],
                       "cam_t_w2c": [0.0, 0.0, 650.0], "depth_scale": 0.1,
                       "elev": 30 + 5 * im_id, "mode": 0}
        gts[im_id], infos[im_id] = [], []
        for k, (obj_id, (x, y, w, h), z) in enumerate(parts):
            full = np.zeros((H, W), bool)
            full[y:y + h, x:x + w] = True
            visib = owner == k
            Image.fromarray((visib * 255).astype(np.uint8)).save(
                os.path.join(SCENE, "mask_visib", "%06d_%06d.png" % (im_id, k)))
            gts[im_id].append({"cam_R_m2c": [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0],
                               "cam_t_m2c": [x - 16.0, y - 12.5, z / 10.0],
                               "obj_id": obj_id})
            count_all, count_visib = int(full.sum()), int(visib.sum())
            infos[im_id].append({"bbox_obj": bop_box(full), "bbox_visib": bop_box(visib),
                                 "px_count_all": count_all,
                                 "px_count_valid": int((full & (depth > 0)).sum()),
                                 "px_count_visib": count_visib,
                                 "visib_fract": count_visib / count_all})
    save_json(os.path.join(SCENE, "scene_camera.json"), cams)
    save_json(os.path.join(SCENE, "scene_gt.json"), gts)
    save_json(os.path.join(SCENE, "scene_gt_info.json"), infos)


if __name__ == "__main__":
    main()
