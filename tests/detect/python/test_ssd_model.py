"""The PyTorch SSD-MobileNetV2: TF SAME padding, the port of the OIDv4 TFLite detector against
outputs recorded from the TFLite interpreter, weight loading, class-head initialisation, loss."""
import math
import unittest

import numpy as np
import torch
from PIL import Image

from detect_test_paths import models_dir_from_argv

MODELS = models_dir_from_argv()
from detect import ssd_model as sm  # noqa: E402
from detect.tflite_reader import TfliteModel  # noqa: E402
from detect.train import ssd_loss  # noqa: E402

# tflite-runtime 2.14 on the centre 300x300 crop of backgrounds/val_101085.jpg (x / 127.5 - 1):
# anchor -> (box encodings, first five class logits).
TFLITE_OUTPUTS = {
    541: ((0.65627, 0.67157, 1.36690, -0.92624), (4.91260, -5.59364, -5.20091, -6.41150, -4.93782)),
    1083: ((2.06329, 0.83607, -0.07780, -0.38930), (7.62013, -15.09230, -11.02375, -13.86957, -11.45091)),
    1855: ((0.03421, 1.64385, -0.62747, -0.75058), (0.87491, -3.73725, -3.94739, -4.60827, -0.04588)),
    1916: ((0.01357, 0.11905, 0.13011, -2.23143), (1.89309, -4.00640, -4.56500, -4.50500, -1.11475)),
}


def centre_crop_input():
    rgb = np.asarray(Image.open(MODELS.parent / "backgrounds/val_101085.jpg").convert("RGB"))
    h, w, _ = rgb.shape
    y, x = (h - 300) // 2, (w - 300) // 2
    crop = rgb[y:y + 300, x:x + 300].astype(np.float32) / 127.5 - 1.0
    return torch.from_numpy(crop.transpose(2, 0, 1).copy())[None]


class SamePadding(unittest.TestCase):
    def test_table(self):
        # (size, kernel, stride) -> (before, after, output), TensorFlow's SAME rule.
        cases = {(300, 3, 2): (0, 1, 150), (150, 3, 2): (0, 1, 75), (75, 3, 2): (1, 1, 38),
                 (19, 3, 2): (1, 1, 10), (10, 3, 2): (0, 1, 5), (5, 3, 2): (1, 1, 3),
                 (3, 3, 2): (1, 1, 2), (2, 3, 2): (0, 1, 1), (19, 3, 1): (1, 1, 19),
                 (10, 1, 1): (0, 0, 10)}
        for args, want in cases.items():
            self.assertEqual(sm.same_padding(*args), want, args)

    def test_feature_map_sizes(self):
        m = sm.SSDMobileNetV2()
        self.assertEqual(m.detector.feature_map_sizes, (19, 10, 5, 3, 2, 1))
        self.assertEqual(m.backbone.feature_channels, (576, 1280))


class Oidv4Port(unittest.TestCase):
    def test_matches_tflite(self):
        m = sm.SSDMobileNetV2(num_classes=23).eval()
        self.assertEqual(sm.load_detector_from_tflite(m, sm.SSD_OIDV4, class_heads=True,
                                                      backbone=True), 72)
        self.assertEqual(sum(p.numel() for p in m.parameters()), 4951996)
        with torch.no_grad():
            boxes, logits = m(centre_crop_input())
        self.assertEqual(tuple(boxes.shape), (1, 1917, 4))
        self.assertEqual(tuple(logits.shape), (1, 1917, 24))
        for a, (b, c) in TFLITE_OUTPUTS.items():
            np.testing.assert_allclose(boxes[0, a].numpy(), b, atol=2e-3, err_msg="anchor %d" % a)
            np.testing.assert_allclose(logits[0, a, :5].numpy(), c, atol=2e-3,
                                       err_msg="anchor %d" % a)


class TransferModel(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        torch.manual_seed(0)
        cls.m = sm.build_model(23, backbone="imagenet", class_heads="random").eval()

    def test_backbone_is_imagenet(self):
        tfl = TfliteModel.read(sm.MOBILENET_V2_IMAGENET)
        conv = [op for op in tfl.operators if op.op == "CONV_2D"][5]
        w = tfl.array(tfl.tensors[conv.inputs[1]]).transpose(0, 3, 1, 2)
        dst = [c for c in self.m.backbone.convs() if not c.depthwise][5]
        np.testing.assert_array_equal(dst.conv.weight.detach().numpy(), w)

    def test_fresh_class_heads_start_at_background(self):
        with torch.no_grad():
            _, logits = self.m(centre_crop_input())
        p_bg = torch.softmax(logits[0], -1)[:, 0]
        self.assertGreater(float(p_bg.min()), 0.9)
        self.assertAlmostEqual(float(p_bg.median()), 0.99, delta=0.01)

    def test_class_heads_of_other_width_refused(self):
        m = sm.SSDMobileNetV2(num_classes=5)
        with self.assertRaisesRegex(ValueError, "class predictor 0 has 72 outputs"):
            sm.load_detector_from_tflite(m, sm.SSD_OIDV4, class_heads=True)
        self.assertEqual(sm.load_detector_from_tflite(m, sm.SSD_OIDV4, class_heads=False), 14)


class Loss(unittest.TestCase):
    def test_hard_negatives_three_per_positive(self):
        labels = torch.zeros(2, 1917, dtype=torch.long)
        labels[0, [3, 10, 400]] = torch.tensor([1, 2, 23])
        labels[1, [1000, 1500]] = 7
        logits = torch.zeros(2, 1917, 24)      # every anchor: cross-entropy log(24)
        targets = torch.zeros(2, 1917, 4)
        boxes = torch.zeros(2, 1917, 4)
        boxes[0, 3] = torch.tensor([0.5, 0.0, 0.0, 2.0])   # smooth L1: 0.125 + 1.5
        loc, cls = ssd_loss(boxes, logits, labels, targets)
        self.assertAlmostEqual(float(loc), 1.625 / 5, places=6)
        # 5 positives, 9 negatives for image 0 (3 per positive), 8 for image 1 (the minimum).
        self.assertAlmostEqual(float(cls), (5 + 9 + 8) / 5 * math.log(24), places=5)
        # The hardest negatives are the ones taken.
        logits[1, 50, 3] = 10.0
        _, cls2 = ssd_loss(boxes, logits, labels, targets)
        self.assertGreater(float(cls2), float(cls) + 1.0)


if __name__ == "__main__":
    unittest.main()
