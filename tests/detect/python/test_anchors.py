"""SSD anchors (TF OD API ssd_mobilenet_v2 layout), sidecar file and box coder."""
import math
import tempfile
import unittest
from pathlib import Path

import numpy as np

from detect import anchors as anc


class Layout(unittest.TestCase):
    def setUp(self):
        self.a = anc.generate()

    def test_count_and_layers(self):
        self.assertEqual(self.a.shape, (1917, 4))
        self.assertEqual(anc.anchors_per_cell(), [3, 6, 6, 6, 6, 6])
        self.assertEqual(sum(s * s * n for s, n in zip(anc.FEATURE_MAP_SIZES, anc.anchors_per_cell())),
                         1917)

    def test_first_cell_reduced_boxes(self):
        c = 0.5 / 19
        np.testing.assert_allclose(self.a[0], [c, c, 0.1, 0.1], rtol=1e-6)
        r = math.sqrt(2)
        np.testing.assert_allclose(self.a[1], [c, c, 0.2 / r, 0.2 * r], rtol=1e-6)
        np.testing.assert_allclose(self.a[2], [c, c, 0.2 * r, 0.2 / r], rtol=1e-6)
        # Order within a layer: row, then column, then anchor.
        np.testing.assert_allclose(self.a[3, :2], [c, 3 * c], rtol=1e-6)
        np.testing.assert_allclose(self.a[3 * 19, :2], [3 * c, c], rtol=1e-6)

    def test_second_layer_and_last(self):
        first = 19 * 19 * 3
        s1, s2 = 0.2 + 0.75 / 5, 0.2 + 1.5 / 5
        np.testing.assert_allclose(self.a[first], [0.05, 0.05, s1, s1], rtol=1e-6)
        np.testing.assert_allclose(self.a[first + 3, 2:], [s1 / math.sqrt(3), s1 * math.sqrt(3)],
                                   rtol=1e-6)
        np.testing.assert_allclose(self.a[first + 5, 2:], [math.sqrt(s1 * s2)] * 2, rtol=1e-6)
        # The 1x1 layer: scale 0.95, the interpolated box sqrt(0.95 * 1).
        np.testing.assert_allclose(self.a[-6], [0.5, 0.5, 0.95, 0.95], rtol=1e-6)
        np.testing.assert_allclose(self.a[-1], [0.5, 0.5, math.sqrt(0.95), math.sqrt(0.95)],
                                   rtol=1e-6)


class Sidecar(unittest.TestCase):
    def test_round_trip_is_exact(self):
        a = anc.generate()
        with tempfile.TemporaryDirectory() as d:
            p = Path(d) / "anchors.csv"
            anc.write_sidecar(p, a)
            lines = p.read_text().splitlines()
            self.assertEqual(lines[0], "ycenter,xcenter,height,width")
            self.assertEqual(len(lines), 1918)
            np.testing.assert_array_equal(anc.read_sidecar(p), a)

    def test_bad_header(self):
        with tempfile.TemporaryDirectory() as d:
            p = Path(d) / "bad.txt"
            p.write_text("1917\n")
            with self.assertRaisesRegex(ValueError, "ycenter,xcenter,height,width"):
                anc.read_sidecar(p)


class Coder(unittest.TestCase):
    def test_encode_known_values(self):
        a = np.array([[0.5, 0.5, 0.2, 0.4]])
        box = np.array([[0.52, 0.46, 0.4, 0.2]])
        t = anc.encode(box, a)[0]
        np.testing.assert_allclose(t, [10 * 0.02 / 0.2, 10 * -0.04 / 0.4, 5 * math.log(2),
                                       5 * math.log(0.5)], rtol=1e-5)

    def test_round_trip(self):
        a = anc.generate()
        rng = np.random.RandomState(3)
        boxes = np.column_stack([rng.uniform(0, 1, (1917, 2)), rng.uniform(0.02, 1, (1917, 2))])
        np.testing.assert_allclose(anc.decode(anc.encode(boxes, a), a), boxes, rtol=1e-5, atol=1e-6)

    def test_match(self):
        a = anc.generate()
        gt = np.array([[0.1, 0.1, 0.5, 0.4], [0.9, 0.9, 0.93, 0.94]], np.float32)  # corners
        labels, targets = anc.match(gt, np.array([5, 9]), a)
        self.assertGreater(int((labels == 5).sum()), 1)
        self.assertEqual(int((labels == 9).sum()), 1)  # tiny box: only its forced best anchor
        ious = anc.iou(anc.corners(a), gt)
        self.assertTrue((ious[labels == 5, 0] >= 0.5).all())
        i = int(np.nonzero(labels == 9)[0][0])
        self.assertEqual(i, int(ious[:, 1].argmax()))
        box = anc.decode(targets[i:i + 1], a[i:i + 1])
        np.testing.assert_allclose(anc.corners(box)[0], gt[1], atol=1e-6)
        self.assertTrue((targets[labels == 0] == 0).all())
        empty = anc.match(np.zeros((0, 4), np.float32), np.zeros(0, np.int64), a)
        self.assertEqual(int(empty[0].sum()), 0)


if __name__ == "__main__":
    unittest.main()
