"""The ONNX export read by OpenCV's DNN module (Debian python3-opencv, OpenCV 4.6): names,
shapes, no Identity node, and the same outputs as PyTorch on a photograph."""
import tempfile
import unittest
from pathlib import Path

import numpy as np
import torch

from detect_test_paths import models_dir_from_argv

MODELS = models_dir_from_argv()
import onnx  # noqa: E402
from detect import ssd_model as sm  # noqa: E402
from detect.export_onnx import check_with_opencv, export, strip_identities  # noqa: E402
from PIL import Image  # noqa: E402


class OnnxForOpenCV(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        torch.manual_seed(0)
        cls.model = sm.build_model(23, backbone="imagenet", class_heads="random").eval()
        cls.tmp = tempfile.TemporaryDirectory()
        cls.path = export(cls.model, Path(cls.tmp.name) / "ssd.onnx")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_graph(self):
        m = onnx.load(str(self.path))
        self.assertEqual(m.opset_import[0].version, 10)
        self.assertEqual([i.name for i in m.graph.input], ["image"])
        dims = lambda v: [d.dim_value for d in v.type.tensor_type.shape.dim]  # noqa: E731
        self.assertEqual(dims(m.graph.input[0]), [1, 3, 300, 300])
        self.assertEqual({o.name: dims(o) for o in m.graph.output},
                         {"box_encodings": [1, 1917, 4], "class_logits": [1, 1917, 24]})
        self.assertNotIn("Identity", {n.op_type for n in m.graph.node})

    def test_opencv_matches_pytorch(self):
        rgb = np.asarray(Image.open(MODELS.parent / "backgrounds/val_101085.jpg").convert("RGB"))
        diff = check_with_opencv(self.model, self.path, rgb)
        self.assertLess(diff, 5e-4)

    def test_strip_identities(self):
        from onnx import helper, TensorProto
        x = helper.make_tensor_value_info("x", TensorProto.FLOAT, [1, 2])
        y = helper.make_tensor_value_info("y", TensorProto.FLOAT, [1, 2])
        g = helper.make_graph([helper.make_node("Identity", ["x"], ["x1"]),
                               helper.make_node("Relu", ["x1"], ["y"])], "g", [x], [y])
        m = helper.make_model(g, opset_imports=[helper.make_opsetid("", 10)])
        out = onnx.load_from_string(strip_identities(m.SerializeToString()))
        self.assertEqual([n.op_type for n in out.graph.node], ["Relu"])
        self.assertEqual(list(out.graph.node[0].input), ["x"])


if __name__ == "__main__":
    unittest.main()
