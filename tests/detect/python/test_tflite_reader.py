"""The TFLite flatbuffer reader against known facts of the shared models."""
import unittest

import numpy as np

from detect_test_paths import models_dir_from_argv

MODELS = models_dir_from_argv()
from detect.tflite_reader import TfliteModel  # noqa: E402

OIDV4 = MODELS / "ssd_mobilenetv2_oidv4/object_detection_ssd_mobilenetv2_oidv4_fp16.tflite"
V2_INT8 = MODELS / "mobilenet_imagenet/tf2_mobilenet_v2_1.0_224_ptq.tflite"
V1_UINT8 = MODELS / "mobilenet_imagenet/mobilenet_v1_1.0_224_quant_embedding_extractor.tflite"


def first_conv(m):
    return next(op for op in m.operators if op.op == "CONV_2D")


class Fp16Detector(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.m = TfliteModel.read(OIDV4)

    def test_graph(self):
        m = self.m
        self.assertEqual(len(m.tensors), 389)
        self.assertEqual(len(m.operators), 241)
        self.assertEqual(m.tensors[m.inputs[0]].name, "normalized_input_image_tensor")
        self.assertEqual(m.tensors[m.inputs[0]].shape, (1, 300, 300, 3))
        outs = {m.tensors[i].name: m.tensors[i].shape for i in m.outputs}
        self.assertEqual(outs, {"raw_outputs/box_encodings": (1, 1917, 4),
                                "raw_outputs/class_predictions": (1, 1917, 24)})
        convs = [op for op in m.operators if op.op in ("CONV_2D", "DEPTHWISE_CONV_2D")]
        self.assertEqual(len(convs), 72)  # 52 MobileNetV2 + 8 extra layers + 12 predictors

    def test_first_conv(self):
        op = first_conv(self.m)
        self.assertEqual((op.padding, op.stride, op.activation), ("SAME", (2, 2), "RELU6"))
        w = self.m.tensors[op.inputs[1]]
        # The conv reads the DEQUANTIZE output; its data is the FLOAT16 constant behind it.
        self.assertEqual(self.m.producer(w.index).op, "DEQUANTIZE")
        self.assertEqual(self.m.tensors[self.m.producer(w.index).inputs[0]].type_name, "FLOAT16")
        a = self.m.array(w)
        self.assertEqual(a.shape, (32, 3, 3, 3))
        self.assertEqual(a.dtype, np.float32)
        self.assertTrue(np.isfinite(a).all())
        # Batch norm folded into the weights: larger than He initialisation, but bounded.
        self.assertTrue(0.3 < a.std() < 5.0, a.std())
        fp16 = self.m.raw(w)
        self.assertEqual(fp16.dtype, np.float16)
        np.testing.assert_array_equal(fp16.astype(np.float32), a)

    def test_all_constants_finite(self):
        c = self.m.constants()
        self.assertGreater(len(c), 140)
        for name, v in c.items():
            if v.dtype.kind == "f":
                self.assertTrue(np.isfinite(v).all(), name)


class Int8PerChannel(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.m = TfliteModel.read(V2_INT8)

    def test_graph(self):
        self.assertEqual(len(self.m.tensors), 177)
        self.assertEqual(len(self.m.operators), 68)
        inp = self.m.tensors[self.m.inputs[0]]
        self.assertEqual((inp.shape, inp.type_name), ((1, 224, 224, 3), "UINT8"))
        self.assertAlmostEqual(float(inp.scale[0]), 1 / 127.5, places=6)
        self.assertEqual(int(inp.zero_point[0]), 127)

    def test_first_conv_dequantised_per_channel(self):
        op = first_conv(self.m)
        w = self.m.tensors[op.inputs[1]]
        self.assertEqual((w.type_name, w.shape, w.scale.size, w.quantized_dimension),
                         ("INT8", (32, 3, 3, 3), 32, 0))
        q = self.m.raw(w).astype(np.float64)
        a = self.m.array(w)
        for ch in (0, 17, 31):
            np.testing.assert_allclose(a[ch], (q[ch] - w.zero_point[ch]) * w.scale[ch], rtol=1e-6)
        self.assertTrue(0.1 < a.std() < 5.0, a.std())
        # Per-channel scales are max|w| / 127: each live channel reaches +-127 (this model has
        # 7 dead channels, all zero, in its first convolution).
        peak = np.abs(q).reshape(32, -1).max(1)
        self.assertEqual(set(peak.tolist()), {0, 127})
        self.assertEqual(int((peak == 127).sum()), 25)

    def test_bias_scale_is_input_times_weight_scale(self):
        op = first_conv(self.m)
        x = self.m.tensors[op.inputs[0]]
        w, b = self.m.tensors[op.inputs[1]], self.m.tensors[op.inputs[2]]
        self.assertEqual(b.type_name, "INT32")
        np.testing.assert_allclose(b.scale, x.scale[0] * w.scale, rtol=1e-5)
        self.assertTrue(np.isfinite(self.m.array(b)).all())


class Uint8PerTensor(unittest.TestCase):
    def test_first_conv(self):
        m = TfliteModel.read(V1_UINT8)
        self.assertEqual((len(m.tensors), len(m.operators)), (83, 28))
        w = m.tensors[first_conv(m).inputs[1]]
        self.assertEqual((w.type_name, w.shape, w.scale.size), ("UINT8", (32, 3, 3, 3), 1))
        q = m.raw(w).astype(np.float64)
        a = m.array(w)
        np.testing.assert_allclose(a, (q - w.zero_point[0]) * w.scale[0], rtol=1e-6)
        self.assertTrue(0.1 < a.std() < 5.0, a.std())


class BadInput(unittest.TestCase):
    def test_not_tflite(self):
        with self.assertRaisesRegex(ValueError, "not a TFLite flatbuffer"):
            TfliteModel(b"\x00" * 64)

    def test_unknown_tensor(self):
        with self.assertRaisesRegex(KeyError, "no tensor named"):
            TfliteModel.read(V1_UINT8).tensor("nope")


if __name__ == "__main__":
    unittest.main()
