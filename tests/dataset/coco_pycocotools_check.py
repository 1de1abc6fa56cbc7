#!/usr/bin/env python3
"""The COCO file of host/dataset read by pycocotools, the reference implementation.

Usage: coco_pycocotools_check.py FIXTURE_WRITER SCRATCH_FOLDER
       coco_pycocotools_check.py --dataset ROOT
The first runs FIXTURE_WRITER (flexsight_write_coco_fixture) into SCRATCH_FOLDER/dataset, then
checks with pycocotools that COCO() loads the file, that annToMask gives each visible
mask the writer stored in mask_visib/, that bbox and area equal maskUtils.toBbox and
maskUtils.area, that every counts string is the one maskUtils.encode makes, that the
strings worked out by hand in tests/dataset/test_coco_rle.cpp are pycocotools' too, and
that each file_name leads to the image. The second checks a data set `flexsight synth`
made (the same checks, less the fixture's known strings and count). Fails (never skips) without pycocotools: CMake
runs it with FLEXSIGHT_COCO_PYTHON, the venv scripts/setup.sh makes.
"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np
from PIL import Image

try:
    from pycocotools import mask as mask_utils
    from pycocotools.coco import COCO
except ImportError as error:
    sys.exit("FAIL: pycocotools is not installed for %s (%s); run scripts/setup.sh"
             % (sys.executable, error))

# The same masks and strings as test_coco_rle.cpp's known_rles().
def rows(*lines):
    return np.array([[c == "1" for c in line] for line in lines], dtype=np.uint8)

def column(*runs):
    values = []
    for i, run in enumerate(runs):
        values += [i % 2] * run
    return np.array(values, dtype=np.uint8).reshape(-1, 1)

HAND_WORKED = [
    (rows("0101", "0100", "0010"), "3230O"),
    (rows("000", "000"), "6"),
    (rows("11", "11"), "04"),
    (column(35, 5), "S15"),
    (column(44, 6), "\\16"),
    (column(1, 5, 3, 2), "153M"),
]
# The fixture's first four images hold the first and the last three of those masks.
FIXTURE_STRINGS = {0: "3230O", 1: "S15", 2: "\\16", 3: "153M"}

failures = []

def check(condition, message):
    if not condition:
        failures.append(message)

def encode(mask):
    return mask_utils.encode(np.asfortranarray(mask.astype(np.uint8)))

def main():
    fixture = sys.argv[1] != "--dataset"
    for mask, text in HAND_WORKED:
        got = encode(mask)["counts"].decode("ascii")
        check(got == text, "pycocotools encodes %s as %r, the hand-worked string is %r"
              % (mask.tolist(), got, text))

    if fixture:
        writer, scratch = sys.argv[1], sys.argv[2]
        root = os.path.join(scratch, "dataset")
        shutil.rmtree(root, ignore_errors=True)
        subprocess.run([writer, root], check=True)
    else:
        root = sys.argv[2]
    coco_path = os.path.join(root, "coco_instances.json")
    coco = COCO(coco_path)
    with open(coco_path) as f:
        raw = json.load(f)
    check(len(raw["images"]) == 10 if fixture else len(raw["images"]) > 0, "expected 10 images, found %d" % len(raw["images"]))
    check([a["id"] for a in raw["annotations"]] == list(range(1, len(raw["annotations"]) + 1)),
          "annotation ids are not 1, 2, ...")

    for image in coco.loadImgs(coco.getImgIds()):
        path = os.path.join(root, image["file_name"])
        check(os.path.exists(path), "file_name %s does not exist" % path)
        check(Image.open(path).size == (image["width"], image["height"]), "size of " + path)
        # The writer's visible masks of this image, in gt order, those with a pixel set.
        scene = os.path.join(root, "%06d" % image["scene_id"], "mask_visib")
        prefix = "%06d_" % image["im_id"]
        masks = [np.array(Image.open(os.path.join(scene, name))) > 0
                 for name in sorted(os.listdir(scene)) if name.startswith(prefix)]
        visible = [m for m in masks if m.any()]
        annotations = coco.loadAnns(coco.getAnnIds(imgIds=[image["id"]]))
        annotations.sort(key=lambda a: a["id"])
        check(len(annotations) == len(visible), "image %d: %d annotations for %d visible parts"
              % (image["id"], len(annotations), len(visible)))
        for annotation, mask in zip(annotations, visible):
            where = "annotation %d" % annotation["id"]
            check(np.array_equal(coco.annToMask(annotation) > 0, mask), where + ": annToMask")
            rle = annotation["segmentation"]
            check(rle["counts"] == encode(mask)["counts"].decode("ascii"), where + ": counts")
            check(list(mask_utils.toBbox(rle)) == annotation["bbox"], where + ": bbox %s vs %s"
                  % (annotation["bbox"], list(mask_utils.toBbox(rle))))
            check(float(mask_utils.area(rle)) == annotation["area"], where + ": area")
            check(annotation["iscrowd"] == 0, where + ": iscrowd")
        if fixture and image["id"] in FIXTURE_STRINGS:
            expected = FIXTURE_STRINGS[image["id"]]
            check([a["segmentation"]["counts"] for a in annotations] == [expected],
                  "image %d: expected the one string %r" % (image["id"], expected))

    for message in failures:
        print("FAIL: " + message)
    if not failures:
        print("pycocotools reads the COCO file as written (%d images, %d annotations)"
              % (len(raw["images"]), len(raw["annotations"])))
    return 1 if failures else 0

if __name__ == "__main__":
    sys.exit(main())
