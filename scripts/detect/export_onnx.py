"""Export an SSD-MobileNetV2 to ONNX for OpenCV's DNN module (4.6), and check that it reads it.

The graph: input `image` [1, 3, 300, 300] float, RGB scaled to [-1, 1] (x / 127.5 - 1; in OpenCV:
cv::dnn::blobFromImage(bgr, 1 / 127.5, {300, 300}, {127.5, 127.5, 127.5}, /*swapRB=*/true)),
outputs `box_encodings` [1, 1917, 4] (ty, tx, th, tw; scale factors 10, 10, 5, 5) and
`class_logits` [1, 1917, C + 1] (background at index 0). Identity nodes
are removed (OpenCV 4.6 rejects some, e.g. one on the graph input). Opset 10 only: with 11,
ReLU6 becomes a Clip with min/max inputs that OpenCV 4.6's importer rejects.

    python3 -m detect.export_onnx --checkpoint run/model.pt -o model.onnx   # a trained model
    python3 -m detect.export_onnx --oidv4 -o oidv4.onnx                      # the OIDv4 detector as is
"""
from __future__ import annotations

import argparse
import io
import sys
from pathlib import Path

import numpy as np
import torch

from .ssd_model import SSD_OIDV4, SSDMobileNetV2, load_detector_from_tflite, preprocess

INPUT_NAME = "image"
OUTPUT_NAMES = ("box_encodings", "class_logits")


def strip_identities(data: bytes) -> bytes:
    """Remove Identity nodes, renaming their consumers' inputs (and graph outputs) to the
    Identity's input."""
    import onnx
    m = onnx.load_from_string(data)
    g = m.graph
    idents = [n for n in g.node if n.op_type == "Identity"]
    if not idents:
        return data
    graph_outputs = {o.name for o in g.output}
    for n in idents:
        src, dst = n.input[0], n.output[0]
        if dst in graph_outputs:
            # Keep the output name: rename the producer's output instead.
            for p in g.node:
                p.output[:] = [dst if o == src else o for o in p.output]
            for c in g.node:
                c.input[:] = [dst if i == src else i for i in c.input]
        else:
            for c in g.node:
                c.input[:] = [src if i == dst else i for i in c.input]
        g.node.remove(n)
    onnx.checker.check_model(m)
    return m.SerializeToString()


def export(model: SSDMobileNetV2, path, opset: int = 10) -> Path:
    model = model.eval()
    x = torch.zeros(1, 3, model.image_size, model.image_size)
    buf = io.BytesIO()
    with torch.no_grad():
        torch.onnx.export(model, x, buf, opset_version=opset, input_names=[INPUT_NAME],
                          output_names=list(OUTPUT_NAMES), do_constant_folding=True)
    data = strip_identities(buf.getvalue())
    path = Path(path)
    path.write_bytes(data)
    return path


def opencv_forward(path, x: torch.Tensor):
    import cv2
    net = cv2.dnn.readNetFromONNX(str(path))
    net.setPreferableBackend(cv2.dnn.DNN_BACKEND_OPENCV)
    net.setPreferableTarget(cv2.dnn.DNN_TARGET_CPU)
    net.setInput(x.numpy())
    return net.forward(list(OUTPUT_NAMES))


def check_with_opencv(model: SSDMobileNetV2, path, rgb: np.ndarray) -> float:
    """Max abs difference between OpenCV's and PyTorch's outputs on one image."""
    x = preprocess(rgb, model.image_size)
    with torch.no_grad():
        ref = [t.numpy() for t in model.eval()(x)]
    out = opencv_forward(path, x)
    diff = 0.0
    for name, a, b in zip(OUTPUT_NAMES, out, ref):
        if a.shape != b.shape:
            raise ValueError("OpenCV output %s has shape %s, PyTorch %s" % (name, a.shape, b.shape))
        diff = max(diff, float(np.abs(a - b).max()))
    return diff


def load_checkpoint(path) -> SSDMobileNetV2:
    ckpt = torch.load(path, map_location="cpu")
    model = SSDMobileNetV2(num_classes=ckpt["num_classes"])
    model.load_state_dict(ckpt["model"])
    return model


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="Export SSD-MobileNetV2 to ONNX and check it in cv2.dnn.")
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("--checkpoint", type=Path, help="a model.pt written by train.py")
    src.add_argument("--oidv4", action="store_true", help="the shared OIDv4 detector, unchanged")
    ap.add_argument("-o", "--output", type=Path, required=True)
    # Opset 11 turns ReLU6 into Clip with min/max inputs, which OpenCV 4.6 fails to import.
    ap.add_argument("--opset", type=int, default=10, choices=(10,))
    ap.add_argument("--check-image", type=Path,
                    default=SSD_OIDV4.parents[2] / "backgrounds/val_101085.jpg",
                    help="photograph for the OpenCV-vs-PyTorch comparison")
    args = ap.parse_args(argv)
    if args.oidv4:
        model = SSDMobileNetV2(num_classes=23)
        load_detector_from_tflite(model, SSD_OIDV4, class_heads=True, backbone=True)
    else:
        model = load_checkpoint(args.checkpoint)
    export(model, args.output, args.opset)
    from PIL import Image
    rgb = np.asarray(Image.open(args.check_image).convert("RGB"))
    diff = check_with_opencv(model, args.output, rgb)
    print("wrote %s; cv2.dnn reads it, max|OpenCV - PyTorch| = %.2e on %s"
          % (args.output, diff, args.check_image.name))
    if diff > 1e-3:
        print("error: OpenCV and PyTorch disagree", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
