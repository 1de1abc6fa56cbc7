"""The Python decoding, NMS and AP@0.5 of detect.detect_eval (what training reports) against the
C++ ones of `flexsight detect` and `flexsight eval-det` on the same inputs, so that a training
run's numbers are the ones the shipped program gives.

Decoding and NMS: the committed tiny_ssd fixture's network outputs (PyTorch's, recorded by
make_fixture_model) decoded in Python, and `flexsight detect` on the fixture picture (OpenCV's
forward, within 1e-4 of PyTorch's): the same detections, boxes within 0.05 px, scores within 1e-4.
AP@0.5: the shipped model's detections on the held-out fixture tless_synth_8 scored by
`flexsight eval-det --results` and by average_precision_50: the same mAP and per-class AP.

    PYTHONPATH=scripts /usr/bin/python3 tests/detect/python/test_detect_eval_matches_cpp.py \
        --flexsight build/flexsight --work /tmp/detect_eval_matches_cpp
"""
import json
import shutil
import subprocess
import unittest
from pathlib import Path

import numpy as np

from detect import anchors as anc
from detect.coco_set import CocoSet
from detect.detect_eval import average_precision_50, decode_detections
from detect_test_paths import path_from_argv

SOURCE = Path(__file__).resolve().parents[3]
TINY = SOURCE / "tests/data/detect/tiny_ssd"
HELD_OUT = SOURCE / "tests/data/detect/tless_synth_8"
SHIPPED = SOURCE / "models/tless-ssd/model.onnx"
FLEXSIGHT = path_from_argv("--flexsight")
WORK = path_from_argv("--work")


def run(*arguments) -> None:
    subprocess.run([str(FLEXSIGHT), *map(str, arguments)], check=True, stdout=subprocess.DEVNULL)


class DecodeAndNms(unittest.TestCase):
    def test_python_decoding_of_the_fixture_outputs_is_what_flexsight_detect_finds(self):
        anchors = anc.read_sidecar(TINY / "anchors.csv")
        boxes = np.fromfile(TINY / "expected_box_encodings.f32", "<f4").reshape(-1, 4)
        logits = np.fromfile(TINY / "expected_class_logits.f32", "<f4").reshape(len(anchors), -1)
        corners, scores, classes = decode_detections(boxes.astype(np.float64),
                                                     logits.astype(np.float64), anchors,
                                                     score_threshold=0.3, nms_iou=0.6,
                                                     max_detections=100)
        category_of = {int(line.split()[0]): int(line.split()[1])
                       for line in (TINY / "labels.txt").read_text().splitlines()[1:]}
        width, height = 317, 241  # image.png (tiny_ssd/README.md)
        expected = [(category_of[int(c)], float(s),
                     [b[1] * width, b[0] * height, (b[3] - b[1]) * width, (b[2] - b[0]) * height])
                    for b, s, c in zip(corners, scores, classes)]

        out = WORK / "tiny_dets.json"
        run("detect", TINY / "image.png", "--model", TINY / "model.onnx", "-o", out,
            "--score", "0.3", "--iou", "0.6", "--top-k", "1024", "--max-detections", "100",
            "--quiet")
        found = json.loads(out.read_text())
        self.assertGreater(len(expected), 0)
        self.assertEqual(len(found), len(expected))
        unmatched = list(found)
        for category, score, box in expected:
            match = next((d for d in unmatched if d["category_id"] == category
                          and abs(d["score"] - score) <= 1e-4
                          and np.allclose(d["bbox"], box, atol=0.05, rtol=0)), None)
            self.assertIsNotNone(match, "no C++ detection for class %d score %.6f box %s"
                                 % (category, score, box))
            unmatched.remove(match)


class AveragePrecision(unittest.TestCase):
    def test_python_ap50_is_what_flexsight_eval_det_reports(self):
        raw = WORK / "held_out_raw.json"
        run("detect", HELD_OUT / "000000" / "rgb", "--model", SHIPPED, "-o", raw,
            "--score", "0.01", "--quiet")
        data = CocoSet(HELD_OUT / "coco_instances.json")
        id_of = {im["file_name"].split("/")[-1]: im["id"] for im in data.images}
        results = []
        for d in json.loads(raw.read_text()):
            d = dict(d)
            d["image_id"] = id_of[Path(d.pop("file_name")).name]
            results.append(d)
        dets_path = WORK / "held_out_dets.json"
        dets_path.write_text(json.dumps(results))
        report_dir = WORK / "eval_det"
        run("eval-det", HELD_OUT, "--results", dets_path, "--out", report_dir, "--overwrite",
            "--quiet")
        report = json.loads((report_dir / "report.json").read_text())

        class_of = {c["id"]: i + 1 for i, c in enumerate(data.categories)}
        per_image = []
        for im in data.images:
            mine = [d for d in results if d["image_id"] == im["id"]]
            w, h = float(im["width"]), float(im["height"])
            per_image.append((
                np.array([[y / h, x / w, (y + bh) / h, (x + bw) / w]
                          for x, y, bw, bh in (d["bbox"] for d in mine)]).reshape(-1, 4),
                np.array([d["score"] for d in mine]),
                np.array([class_of[d["category_id"]] for d in mine], np.int64)))
        mean_ap, aps = average_precision_50(per_image, data.gt, len(data.categories))

        self.assertTrue(0.05 < mean_ap < 0.95, "degenerate fixture: mAP@0.5 %.3f" % mean_ap)
        self.assertAlmostEqual(report["map50"], mean_ap, delta=1e-6)
        for entry in report["classes"]:
            expected = aps.get(class_of[entry["category_id"]])
            if expected is None:
                self.assertIsNone(entry["voc_ap50"], "class %d" % entry["category_id"])
            else:
                self.assertAlmostEqual(entry["voc_ap50"], expected, delta=1e-6,
                                       msg="class %d" % entry["category_id"])


if __name__ == "__main__":
    shutil.rmtree(WORK, ignore_errors=True)
    WORK.mkdir(parents=True)
    unittest.main()
