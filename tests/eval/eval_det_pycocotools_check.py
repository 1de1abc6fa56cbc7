#!/usr/bin/env python3
"""flexsight eval-det against pycocotools' COCOeval, the reference of the COCO metric, and
against a plain Python VOC AP written from the definition in docs/detect.md.

Usage: eval_det_pycocotools_check.py FLEXSIGHT SCRATCH_FOLDER

For each scenario below, made from a fixed seed, the script writes a small COCO data set
(images, coco_instances.json) and detections (jittered copies of the ground truth,
duplicates, false positives, classes without ground truth) in both result forms, runs
`FLEXSIGHT eval-det`, and requires:
  * map50_95, ap50_coco, ap75 and every class's coco_ap within 1e-6 of COCOeval's;
  * map50, map_at_iou_threshold and every class's voc_ap50 within 1e-9 of the VOC AP below;
  * the BOP form of the same detections to give the same report numbers;
  * the class-agnostic figures: coco_ap within 1e-6 of COCOeval's with useCats = 0, ap50
    within 1e-9 of the VOC AP above with every box relabelled one class.
Fails (never skips) without pycocotools: CMake runs it with FLEXSIGHT_COCO_PYTHON, the
venv scripts/setup.sh makes.
"""
import contextlib
import io
import json
import os
import random
import shutil
import subprocess
import sys

import numpy as np
from PIL import Image

try:
    from pycocotools import mask as mask_utils
    from pycocotools.coco import COCO
    from pycocotools.cocoeval import COCOeval
except ImportError as error:
    sys.exit("FAIL: pycocotools is not installed for %s (%s); run scripts/setup.sh"
             % (sys.executable, error))

WIDTH, HEIGHT = 96, 72
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


# ---- the fixture -----------------------------------------------------------------------

def random_box(rng):
    w = rng.randint(6, 40)
    h = rng.randint(6, 30)
    return [rng.randint(0, WIDTH - w), rng.randint(0, HEIGHT - h), w, h]


def box_mask(box):
    mask = np.zeros((HEIGHT, WIDTH), np.uint8)
    x, y, w, h = box
    mask[y:y + h, x:x + w] = 1
    return mask


def uncompressed_rle(mask):
    """COCO's uncompressed RLE (the form of its crowd regions): run lengths, column-major,
    starting with zeros."""
    flat = mask.flatten(order="F")
    counts, value, run = [], 0, 0
    for pixel in flat:
        if pixel == value:
            run += 1
        else:
            counts.append(run)
            value, run = pixel, 1
    counts.append(run)
    return {"size": [HEIGHT, WIDTH], "counts": [int(c) for c in counts]}


def jitter(rng, box, amount):
    x, y, w, h = box
    return [x + rng.gauss(0, amount * w), y + rng.gauss(0, amount * h),
            max(0.5, w * (1 + rng.gauss(0, amount))), max(0.5, h * (1 + rng.gauss(0, amount)))]


def make_scenario(folder, seed, images=12, crowd=False, tied_scores=False, crowded_image=False,
                  iou_ties=False):
    """Writes folder/dataset (images and coco_instances.json), folder/dets.json (COCO
    results) and folder/dets_bop.json (the same detections as BOP results).

    crowd: some boxes are crowd regions. tied_scores: scores rounded to tenths.
    crowded_image: the first image gets 150 high-scored false positives of class 2 beside
    its true ones, so COCOeval's cut at 100 per image and class drops true positives.
    iou_ties: images get two boxes of class 3 side by side and a better-scored detection
    exactly between them (the same IoU with both), then one on the left box only: which
    box the first takes decides whether the second is a true positive (COCOeval: the later
    box; VOC as defined here: the first)."""
    rng = random.Random(seed)
    root = os.path.join(folder, "dataset")
    os.makedirs(os.path.join(root, "rgb"))
    categories = [{"id": c, "name": "obj_%02d" % c, "supercategory": "part"} for c in (1, 2, 3, 5, 9)]
    with_truth = [1, 2, 3, 5]  # 9: a class without ground truth (its detections are all wrong)
    # Image ids out of order and with gaps: COCOeval visits them sorted.
    ids = rng.sample(range(1, 1000), images)
    coco = {"images": [], "annotations": [], "categories": categories}
    dets = []
    pixels = np.random.default_rng(seed)
    for n, image_id in enumerate(ids):
        file_name = "rgb/%06d.png" % image_id
        Image.fromarray(pixels.integers(0, 255, (HEIGHT, WIDTH, 3), dtype=np.uint8)).save(
            os.path.join(root, file_name))
        coco["images"].append({"id": image_id, "file_name": file_name, "width": WIDTH,
                               "height": HEIGHT, "scene_id": n // 5, "im_id": n % 5})
        truth = []
        for _ in range(rng.randint(0, 6)):
            category = rng.choice(with_truth)
            box = random_box(rng)
            # Some boxes near another of the same class: overlaps for the matching to sort out.
            if truth and rng.random() < 0.3:
                other = rng.choice(truth)
                category = other[0]
                box = [min(WIDTH - 6, max(0, other[1][0] + rng.randint(-6, 6))),
                       min(HEIGHT - 6, max(0, other[1][1] + rng.randint(-6, 6))), 6, 6]
                box[2] = rng.randint(6, WIDTH - box[0])
                box[3] = rng.randint(6, HEIGHT - box[1])
            is_crowd = crowd and rng.random() < 0.2
            mask = box_mask(box)
            segmentation = uncompressed_rle(mask) if is_crowd else mask_utils.encode(
                np.asfortranarray(mask))
            if not is_crowd:
                segmentation["counts"] = segmentation["counts"].decode("ascii")
            coco["annotations"].append({
                "id": len(coco["annotations"]) + 1, "image_id": image_id, "category_id": category,
                "bbox": [float(v) for v in box], "area": float(mask.sum()),
                "segmentation": segmentation, "iscrowd": int(is_crowd)})
            truth.append((category, box))
        if crowded_image and n == 0:
            for _ in range(3):
                box = random_box(rng)
                mask = box_mask(box)
                segmentation = mask_utils.encode(np.asfortranarray(mask))
                segmentation["counts"] = segmentation["counts"].decode("ascii")
                coco["annotations"].append({
                    "id": len(coco["annotations"]) + 1, "image_id": image_id, "category_id": 2,
                    "bbox": [float(v) for v in box], "area": float(mask.sum()),
                    "segmentation": segmentation, "iscrowd": 0})
                truth.append((2, box))
        detections = []
        if iou_ties and rng.random() < 0.6:
            x, y = rng.randint(0, 30), rng.randint(0, 40)
            for box in ([x, y, 20, 20], [x + 10, y, 20, 20]):
                mask = box_mask(box)
                segmentation = mask_utils.encode(np.asfortranarray(mask))
                segmentation["counts"] = segmentation["counts"].decode("ascii")
                coco["annotations"].append({
                    "id": len(coco["annotations"]) + 1, "image_id": image_id, "category_id": 3,
                    "bbox": [float(v) for v in box], "area": float(mask.sum()),
                    "segmentation": segmentation, "iscrowd": 0})
            dets.append({"image_id": image_id, "category_id": 3,
                         "bbox": [x + 5.0, float(y), 20.0, 20.0], "score": 0.99})
            dets.append({"image_id": image_id, "category_id": 3,
                         "bbox": [float(x), float(y), 20.0, 20.0], "score": 0.98})
        for category, box in truth:
            if rng.random() < 0.85:
                detections.append((category, jitter(rng, box, rng.choice([0.02, 0.05, 0.15]))))
            if rng.random() < 0.3:  # a duplicate
                detections.append((category, jitter(rng, box, 0.1)))
            if rng.random() < 0.15:  # the right place, the wrong class
                detections.append((rng.choice([1, 2, 3, 5, 9]), jitter(rng, box, 0.05)))
        for _ in range(rng.randint(0, 4)):  # false positives anywhere
            detections.append((rng.choice([1, 2, 3, 5, 9]), [float(v) for v in random_box(rng)]))
        rng.shuffle(detections)
        for category, box in detections:
            score = rng.random()
            if crowded_image and n == 0:
                score *= 0.5
            if tied_scores:
                score = round(score * 10) / 10
            dets.append({"image_id": image_id, "category_id": category,
                         "bbox": [round(v, 3) for v in box], "score": score})
        if crowded_image and n == 0:  # more than COCOeval's 100 per image and class
            for _ in range(150):
                dets.append({"image_id": image_id, "category_id": 2,
                             "bbox": [float(v) for v in random_box(rng)],
                             "score": 0.5 + 0.5 * rng.random()})
    rng.shuffle(coco["images"])
    with open(os.path.join(root, "coco_instances.json"), "w") as f:
        json.dump(coco, f)
    with open(os.path.join(folder, "dets.json"), "w") as f:
        json.dump(dets, f)
    scene_of = {im["id"]: (im["scene_id"], im["im_id"]) for im in coco["images"]}
    bop = [{"scene_id": scene_of[d["image_id"]][0], "image_id": scene_of[d["image_id"]][1],
            "category_id": d["category_id"], "bbox": d["bbox"], "score": d["score"], "time": 0.01}
           for d in dets]
    with open(os.path.join(folder, "dets_bop.json"), "w") as f:
        json.dump(bop, f)
    return root


# ---- the references --------------------------------------------------------------------

def pycocotools_scores(coco_path, dets_path, use_categories=True):
    """COCOeval's stats[0:3] and each class's AP@[.5:.95] (mean of its precision entries)."""
    with contextlib.redirect_stdout(io.StringIO()):
        gt = COCO(coco_path)
        dt = gt.loadRes(dets_path)
        evaluation = COCOeval(gt, dt, "bbox")
        evaluation.params.useCats = 1 if use_categories else 0
        evaluation.evaluate()
        evaluation.accumulate()
        evaluation.summarize()
    precision = evaluation.eval["precision"][:, :, :, 0, -1]  # area all, maxDets 100
    per_class = {}
    for k, category in enumerate(evaluation.params.catIds):
        p = precision[:, :, k]
        per_class[category] = float(np.mean(p)) if (p > -1).any() else None
    return [float(s) for s in evaluation.stats[:3]], per_class


def iou(d, g, crowd):
    ix = min(d[0] + d[2], g[0] + g[2]) - max(d[0], g[0])
    iy = min(d[1] + d[3], g[1] + g[3]) - max(d[1], g[1])
    if ix <= 0 or iy <= 0:
        return 0.0
    inter = ix * iy
    return inter / (d[2] * d[3] if crowd else d[2] * d[3] + g[2] * g[3] - inter)


def voc_aps(coco_path, dets_path, threshold):
    """VOC all-point AP per class with ground truth, as docs/detect.md defines it: every
    detection of the class, best first (ties: images by id, then file order), takes the
    unmatched non-crowd box with the highest IoU >= threshold; else ignored on a crowd
    region, else a false positive."""
    with open(coco_path) as f:
        coco = json.load(f)
    with open(dets_path) as f:
        dets = json.load(f)
    order = {image_id: n for n, image_id in enumerate(sorted(im["id"] for im in coco["images"]))}
    aps = {}
    for category in sorted(c["id"] for c in coco["categories"]):
        truth = {}
        for a in coco["annotations"]:
            if a["category_id"] == category:
                truth.setdefault(a["image_id"], []).append([a["bbox"], bool(a["iscrowd"]), False])
        positives = sum(1 for boxes in truth.values() for b in boxes if not b[1])
        if positives == 0:
            continue
        mine = [(d["score"], order[d["image_id"]], i, d) for i, d in enumerate(dets)
                if d["category_id"] == category]
        mine.sort(key=lambda r: (-r[0], r[1], r[2]))
        tp, fp = [], []
        for _, _, _, d in mine:
            boxes = truth.get(d["image_id"], [])
            best, best_iou = None, -1.0
            for b in boxes:
                if not b[1] and not b[2]:
                    value = iou(d["bbox"], b[0], False)
                    if value > best_iou:
                        best, best_iou = b, value
            if best is not None and best_iou >= threshold:
                best[2] = True
                tp.append(1), fp.append(0)
            elif any(b[1] and iou(d["bbox"], b[0], True) >= threshold for b in boxes):
                continue
            else:
                tp.append(0), fp.append(1)
        tp, fp = np.cumsum(tp), np.cumsum(fp)
        recall = tp / positives
        precision = tp / np.maximum(tp + fp, np.finfo(np.float64).eps)
        # The VOC devkit's all-point interpolation (voc_ap with use_07_metric=False).
        mrec = np.concatenate(([0.0], recall, [1.0]))
        mpre = np.concatenate(([0.0], precision, [0.0]))
        for i in range(mpre.size - 1, 0, -1):
            mpre[i - 1] = max(mpre[i - 1], mpre[i])
        steps = np.where(mrec[1:] != mrec[:-1])[0]
        aps[category] = float(np.sum((mrec[steps + 1] - mrec[steps]) * mpre[steps + 1]))
    return aps


def one_class_copies(coco_path, dets_path, folder):
    """The data set and detections with every box in category 1, boxes ordered by their
    category first (stable), as eval-det and COCOeval (useCats = 0) pool an image's boxes."""
    with open(coco_path) as f:
        coco = json.load(f)
    with open(dets_path) as f:
        dets = json.load(f)
    coco["annotations"] = sorted(coco["annotations"], key=lambda a: a["category_id"])
    dets = sorted(dets, key=lambda d: d["category_id"])
    for box in coco["annotations"] + dets:
        box["category_id"] = 1
    coco["categories"] = [{"id": 1, "name": "part"}]
    paths = os.path.join(folder, "coco_one_class.json"), os.path.join(folder, "dets_one_class.json")
    for path, data in zip(paths, (coco, dets)):
        with open(path, "w") as f:
            json.dump(data, f)
    return paths


def compare_class_agnostic(name, folder, coco_path, dets, ours):
    agnostic = ours["class_agnostic"]
    stats, _ = pycocotools_scores(coco_path, dets, use_categories=False)
    check(abs(agnostic["coco_ap"] - stats[0]) <= 1e-6,
          "%s: class-agnostic coco_ap is %.9f, pycocotools (useCats 0) says %.9f" % (name, agnostic["coco_ap"], stats[0]))
    voc = voc_aps(*one_class_copies(coco_path, dets, folder), 0.5)
    check(abs(agnostic["ap50"] - voc[1]) <= 1e-9,
          "%s: class-agnostic ap50 is %.9f, the Python VOC AP of one class %.9f" % (name, agnostic["ap50"], voc[1]))
    return agnostic["ap50"], agnostic["coco_ap"], stats[0]


# ---- the comparison --------------------------------------------------------------------

def run_eval_det(flexsight, dataset, dets, out, threshold):
    command = [flexsight, "eval-det", dataset, "--results", dets, "--out", out,
               "--iou-threshold", str(threshold)]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        failures.append("%s failed (%d): %s" % (" ".join(command), result.returncode, result.stderr))
        return None
    with open(os.path.join(out, "report.json")) as f:
        return json.load(f)


def compare(name, folder, flexsight, threshold, **options):
    root = make_scenario(folder, **options)
    coco_path = os.path.join(root, "coco_instances.json")
    dets = os.path.join(folder, "dets.json")
    ours = run_eval_det(flexsight, root, dets, os.path.join(folder, "out"), threshold)
    ours_bop = run_eval_det(flexsight, root, os.path.join(folder, "dets_bop.json"),
                            os.path.join(folder, "out_bop"), threshold)
    if ours is None or ours_bop is None:
        return
    stats, coco_per_class = pycocotools_scores(coco_path, dets)
    for key, theirs in zip(("map50_95", "ap50_coco", "ap75"), stats):
        check(abs(ours[key] - theirs) <= 1e-6,
              "%s: %s is %.9f, pycocotools says %.9f" % (name, key, ours[key], theirs))
    voc50 = voc_aps(coco_path, dets, 0.5)
    voc_t = voc_aps(coco_path, dets, threshold)
    check(abs(ours["map50"] - np.mean(list(voc50.values()))) <= 1e-9,
          "%s: map50 is %.9f, the Python VOC AP %.9f" % (name, ours["map50"], np.mean(list(voc50.values()))))
    check(abs(ours["map_at_iou_threshold"] - np.mean(list(voc_t.values()))) <= 1e-9,
          "%s: map_at_iou_threshold is %.9f, the Python VOC AP %.9f"
          % (name, ours["map_at_iou_threshold"], np.mean(list(voc_t.values()))))
    for entry in ours["classes"]:
        category = entry["category_id"]
        theirs = coco_per_class.get(category)
        if theirs is None:
            check(entry["coco_ap"] is None, "%s: class %d has no ground truth, coco_ap %r"
                  % (name, category, entry["coco_ap"]))
        else:
            check(entry["coco_ap"] is not None and abs(entry["coco_ap"] - theirs) <= 1e-6,
                  "%s: class %d coco_ap %r, pycocotools %.9f" % (name, category, entry["coco_ap"], theirs))
        expected = voc50.get(category)
        got = entry["voc_ap50"]
        check((expected is None and got is None) or
              (expected is not None and got is not None and abs(got - expected) <= 1e-9),
              "%s: class %d voc_ap50 %r, the Python VOC AP %r" % (name, category, got, expected))
    for key in ("map50", "map50_95", "ap50_coco", "ap75", "map_at_iou_threshold", "classes"):
        theirs = ours_bop[key]
        if key == "classes":
            check([{k: v for k, v in c.items()} for c in ours[key]] == theirs,
                  "%s: the BOP form of the detections scores differently per class" % name)
        else:
            check(ours[key] == theirs, "%s: %s is %r from COCO results, %r from BOP results"
                  % (name, key, ours[key], theirs))
    # The fixture must exercise the metrics, not sit at 0 or 1.
    check(0.05 < ours["map50_95"] < 0.95 and 0.05 < ours["map50"] < 0.98,
          "%s: degenerate fixture, map50 %.3f map50_95 %.3f" % (name, ours["map50"], ours["map50_95"]))
    agnostic = compare_class_agnostic(name, folder, coco_path, dets, ours)
    print("%-14s map50 %.6f  map50_95 %.6f (pycocotools %.6f)  ap50 %.6f (%.6f)  ap75 %.6f (%.6f)"
          "  class-agnostic ap50 %.6f  coco %.6f (%.6f)"
          % ((name, ours["map50"], ours["map50_95"], stats[0], ours["ap50_coco"], stats[1],
              ours["ap75"], stats[2]) + agnostic))


def main():
    flexsight, scratch = sys.argv[1], sys.argv[2]
    shutil.rmtree(scratch, ignore_errors=True)
    scenarios = [
        ("plain", 0.5, dict(seed=1)),
        ("more images", 0.5, dict(seed=2, images=30)),
        ("tied scores", 0.5, dict(seed=3, tied_scores=True)),
        ("crowd", 0.5, dict(seed=4, crowd=True)),
        ("over 100", 0.5, dict(seed=5, crowded_image=True)),
        ("iou ties", 0.5, dict(seed=6, iou_ties=True)),
        ("iou 0.7", 0.7, dict(seed=7, crowd=True, tied_scores=True, iou_ties=True)),
    ]
    for name, threshold, options in scenarios:
        folder = os.path.join(scratch, name.replace(" ", "_"))
        os.makedirs(folder)
        compare(name, folder, flexsight, threshold, **options)
    if failures:
        print("FAIL:\n  " + "\n  ".join(failures))
        return 1
    print("eval-det agrees with pycocotools and the Python VOC AP on %d scenarios" % len(scenarios))
    return 0


if __name__ == "__main__":
    sys.exit(main())
