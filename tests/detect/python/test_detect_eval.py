"""Decoding of raw SSD outputs (softmax, per-class NMS) and AP@0.5."""
import math
import unittest

import numpy as np

from detect import anchors as anc
from detect.detect_eval import average_precision_50, decode_detections, nms


class Decode(unittest.TestCase):
    def test_encoded_boxes_come_back_and_duplicates_go(self):
        a = anc.generate()
        gt = np.array([[0.2, 0.3, 0.6, 0.5]], np.float32)
        labels, targets = anc.match(gt, np.array([4]), a)
        logits = np.zeros((1917, 24), np.float32)
        logits[:, 0] = 8.0                     # background everywhere ...
        logits[labels == 4, 4] = 12.0          # ... except the matched anchors: class 4
        boxes, scores, classes = decode_detections(targets, logits, a)
        self.assertEqual(len(boxes), 1)        # matched anchors all decode to gt: NMS keeps one
        np.testing.assert_allclose(boxes[0], gt[0], atol=1e-5)
        self.assertEqual(int(classes[0]), 4)
        self.assertAlmostEqual(float(scores[0]), 1 / (1 + math.exp(-4) + 22 * math.exp(-12)), 5)

    def test_nms_order_and_suppression(self):
        b = np.array([[0, 0, 1, 1], [0, 0, 1, 0.9], [0, 2, 1, 3]], np.float32)
        self.assertEqual(nms(b, np.array([0.5, 0.9, 0.7]), 0.6).tolist(), [1, 2])


class AveragePrecision(unittest.TestCase):
    def setUp(self):
        self.gt = [(np.array([[0.1, 0.1, 0.4, 0.4], [0.5, 0.5, 0.9, 0.9]]), np.array([1, 2])),
                   (np.array([[0.2, 0.2, 0.6, 0.6]]), np.array([1]))]

    def test_perfect(self):
        dets = [(g[0], np.array([0.9] * len(g[1])), g[1]) for g in self.gt]
        m, aps = average_precision_50(dets, self.gt, 23)
        self.assertEqual(aps, {1: 1.0, 2: 1.0})
        self.assertEqual(m, 1.0)

    def test_false_positive_ranked_first_halves_precision(self):
        dets = [(np.array([[0.1, 0.1, 0.4, 0.4], [0.6, 0.0, 0.9, 0.3]]), np.array([0.5, 0.9]),
                 np.array([1, 1])),
                (np.zeros((0, 4)), np.zeros(0), np.zeros(0, np.int64))]
        m, aps = average_precision_50(dets, self.gt, 23)
        # Class 1: FP (0.9) then TP (0.5): recall 0.5 at precision 0.5; second GT never found.
        self.assertAlmostEqual(aps[1], 0.25)
        self.assertEqual(aps[2], 0.0)
        self.assertAlmostEqual(m, 0.125)


if __name__ == "__main__":
    unittest.main()
