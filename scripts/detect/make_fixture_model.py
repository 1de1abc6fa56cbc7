"""Make the tiny SSD fixture of the C++ detector tests (tests/data/detect/tiny_ssd/).

The C++ detector (host/detect/ssd_detector.h) must be tested without a trained model, which is
not in the repository. This script builds a small network with the trained model's contract,
exported by train.py's own export function (export_onnx.export, opset 10, which OpenCV 4.6 reads):

- input "image" [1, 3, 300, 300], RGB scaled to [-1, 1];
- outputs "box_encodings" [1, 1917, 4] and "class_logits" [1, 1917, C + 1], C = 3, with the
  anchors of the real model (anchors.generate()) in the real order: layer (19, 10, 5, 3, 2, 1),
  then row, column, anchor.

Each SSD layer's "feature map" is the image averaged over windows (19x19: 30-pixel windows every
15 pixels; 10, 5, 3, 2, 1: disjoint windows), and its box and class heads are 1x1 convolutions of
those mean colours, as the real heads are 1x1 convolutions of the feature maps. The class heads
are set by hand so that the outputs can be predicted: class k (1 red, 2 green, 3 blue) has logit
4 c_k - 2 (sum of the other two channels) + 0.1 (k - 1), the background a constant 1 (plus 0.05
per anchor slot, so that anchors of one cell do not all tie). A window of pure red (1, -1, -1)
gives red 8, green -3.9, blue -3.8, background 1: softmax 0.999 for red; a grey window gives the
classes 0, 0.1, 0.2 and the background 1 (class scores 0.2 at most, below the 0.3 threshold). The box heads have small seeded random
weights, so boxes move with the image content. Category ids 5, 7, 9 (not 1, 2, 3) make the test
notice a mix-up of class index and category id.

Written (all small):
  model.onnx, anchors.csv, labels.txt, model.json   the model folder, as train.py writes it
  image.png                                         a 317x241 picture: grey, a red and a blue box
  expected_box_encodings.f32, expected_class_logits.f32
                                                    PyTorch's outputs on image.png (raw float32,
                                                    little-endian, 1917 x 4 each), its input made
                                                    by cv2.dnn.blobFromImage exactly as the C++
                                                    detector makes it
  expected_detections.json                          a NumPy decode + per-class NMS of those
                                                    outputs (docs/detect.md's rules), written
                                                    independently of the C++ post-processing
  wrong_box_shape/model.onnx, missing_output/model.onnx
                                                    networks that break the contract, for the
                                                    load checks

    PYTHONPATH=scripts /usr/bin/python3 -m detect.make_fixture_model [-o tests/data/detect/tiny_ssd]
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
import torch
from torch import nn

from . import anchors as anc
from .export_onnx import OUTPUT_NAMES, export
from .train import write_model_json

LABELS = ((5, "red_box"), (7, "green_box"), (9, "blue_box"))  # category id, name
CLASSES = len(LABELS)
# (kernel, stride) of the average pooling that makes each layer's grid from 300 pixels.
POOLS = ((30, 15), (30, 30), (60, 60), (100, 100), (150, 150), (300, 300))
IMAGE_SIZE = (317, 241)  # width, height: not square, not 300, so scaling back is tested
RED_BOX = (40, 60, 140, 150)  # x0, y0, x1, y1 (exclusive), pixels of the fixture image
BLUE_BOX = (200, 30, 290, 100)
# The post-processing of expected_detections.json (the tests use the same values).
SCORE_THRESHOLD, IOU_THRESHOLD, TOP_K, MAX_DETECTIONS = 0.3, 0.6, 1024, 100


class TinySsd(nn.Module):
    image_size = 300  # read by export_onnx.export

    def __init__(self, classes: int = CLASSES, box_channels: int = 4, seed: int = 7):
        super().__init__()
        self.classes = classes
        self.box_channels = box_channels
        per_cell = anc.anchors_per_cell()
        self.pools = nn.ModuleList(nn.AvgPool2d(k, s) for k, s in POOLS)
        self.box_heads = nn.ModuleList(nn.Conv2d(3, a * box_channels, 1) for a in per_cell)
        self.class_heads = nn.ModuleList(nn.Conv2d(3, a * (classes + 1), 1) for a in per_cell)
        generator = torch.Generator().manual_seed(seed)
        with torch.no_grad():
            for head in self.box_heads:
                head.weight.copy_(0.3 * torch.randn(head.weight.shape, generator=generator))
                head.bias.copy_(0.1 * torch.randn(head.bias.shape, generator=generator))
            for head, a in zip(self.class_heads, per_cell):
                w = torch.zeros(a, classes + 1, 3)
                b = torch.zeros(a, classes + 1)
                for k in range(classes):
                    w[:, k + 1, :] = -2.0
                    w[:, k + 1, k % 3] = 4.0
                    b[:, k + 1] = 0.1 * k  # red and blue windows must not tie
                b[:, 0] = 1.0 + 0.05 * torch.arange(a)
                head.weight.copy_(w.reshape(-1, 3, 1, 1))
                head.bias.copy_(b.reshape(-1))

    def forward(self, x):
        boxes, logits = [], []
        for pool, bh, ch in zip(self.pools, self.box_heads, self.class_heads):
            f = pool(x)
            # NCHW -> NHWC, then flatten: (row, column, anchor), as ssd_model.SSDDetector.
            boxes.append(torch.flatten(bh(f).permute(0, 2, 3, 1), 1)
                         .reshape(x.shape[0], -1, self.box_channels))
            logits.append(torch.flatten(ch(f).permute(0, 2, 3, 1), 1)
                          .reshape(x.shape[0], -1, self.classes + 1))
        return torch.cat(boxes, 1), torch.cat(logits, 1)


def fixture_image() -> np.ndarray:
    """BGR, 8-bit: mid grey with a red and a blue box."""
    w, h = IMAGE_SIZE
    img = np.full((h, w, 3), 128, np.uint8)
    x0, y0, x1, y1 = RED_BOX
    img[y0:y1, x0:x1] = (0, 0, 255)
    x0, y0, x1, y1 = BLUE_BOX
    img[y0:y1, x0:x1] = (255, 0, 0)
    return img


def network_input(bgr: np.ndarray) -> torch.Tensor:
    """What the C++ detector feeds the network: cv::dnn::blobFromImage(bgr, 1 / 127.5,
    {300, 300}, {127.5, 127.5, 127.5}, swapRB=true): bilinear resize, no crop."""
    import cv2
    blob = cv2.dnn.blobFromImage(bgr, 1.0 / 127.5, (300, 300), (127.5, 127.5, 127.5), swapRB=True,
                                 crop=False)
    return torch.from_numpy(blob)


def reference_detections(encodings: np.ndarray, logits: np.ndarray, anchors: np.ndarray) -> list:
    """docs/detect.md's post-processing in NumPy (float64): softmax scores, boxes decoded with
    scale factors 10, 10, 5, 5 and clipped to [0, 1], per class the candidates scoring above the
    threshold (best TOP_K, ties by anchor), greedy NMS suppressing IoU > the threshold, the best
    MAX_DETECTIONS overall (score down, class up, anchor up). Boxes x_min, y_min, x_max, y_max."""
    e, a = encodings.astype(np.float64), anchors.astype(np.float64)
    z = logits.astype(np.float64)
    p = np.exp(z - z.max(1, keepdims=True))
    p /= p.sum(1, keepdims=True)
    yc = e[:, 0] / 10 * a[:, 2] + a[:, 0]
    xc = e[:, 1] / 10 * a[:, 3] + a[:, 1]
    h = np.exp(e[:, 2] / 5) * a[:, 2]
    w = np.exp(e[:, 3] / 5) * a[:, 3]
    boxes = np.clip(np.stack([xc - w / 2, yc - h / 2, xc + w / 2, yc + h / 2], 1), 0, 1)

    def iou(i, j):
        bi, bj = boxes[i], boxes[j]
        iw = min(bi[2], bj[2]) - max(bi[0], bj[0])
        ih = min(bi[3], bj[3]) - max(bi[1], bj[1])
        if iw <= 0 or ih <= 0:
            return 0.0
        inter = iw * ih
        area = lambda b: (b[2] - b[0]) * (b[3] - b[1])  # noqa: E731
        return inter / (area(bi) + area(bj) - inter)

    found = []
    for c in range(1, p.shape[1]):
        cand = [i for i in range(len(p)) if p[i, c] > SCORE_THRESHOLD]
        cand.sort(key=lambda i: (-p[i, c], i))
        kept = []
        for i in cand[:TOP_K]:
            if all(iou(i, j) <= IOU_THRESHOLD for j in kept):
                kept.append(i)
        found += [(float(p[i, c]), c - 1, i) for i in kept]
    found.sort(key=lambda d: (-d[0], d[1], d[2]))
    return [{"class_id": c, "anchor": i, "score": s, "box": [float(v) for v in boxes[i]]}
            for s, c, i in found[:MAX_DETECTIONS]]


def check_no_near_ties(found: list, gap: float = 1e-6) -> None:
    """The C++ detector's float32 scores come from OpenCV's outputs, which differ from PyTorch's
    in the last bits (logits by up to ~5e-7, so scores by ~1e-7 at most): two detections whose
    scores lie closer than `gap` could swap places. Equal
    scores are fine (identical windows give identical outputs in both, ties go by class and
    anchor), near-equal ones from different inputs are not."""
    scores = sorted(d["score"] for d in found)
    for a, b in zip(scores, scores[1:]):
        if 0 < b - a < gap:
            raise SystemExit("error: scores %.9f and %.9f are too close to order reliably" % (a, b))


def rename_outputs(src: Path, dst: Path, names: dict) -> None:
    """A copy of the ONNX file `src` whose graph outputs (and the tensors behind them) are
    renamed by `names`."""
    import onnx
    m = onnx.load(str(src))
    for node in m.graph.node:
        node.output[:] = [names.get(o, o) for o in node.output]
        node.input[:] = [names.get(i, i) for i in node.input]
    for output in m.graph.output:
        output.name = names.get(output.name, output.name)
    onnx.checker.check_model(m)
    onnx.save(m, str(dst))


def write_model_folder(model: nn.Module, out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    export(model, out / "model.onnx")
    anc.write_sidecar(out / "anchors.csv")
    lines = ["0 0 background"] + ["%d %d %s" % (i + 1, cid, name)
                                  for i, (cid, name) in enumerate(LABELS)]
    (out / "labels.txt").write_text("\n".join(lines) + "\n")
    write_model_json(out / "model.json")


def main(argv=None) -> int:
    import cv2
    default_out = Path(__file__).resolve().parents[2] / "tests/data/detect/tiny_ssd"
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-o", "--out", type=Path, default=default_out)
    args = ap.parse_args(argv)
    torch.manual_seed(0)
    model = TinySsd().eval()
    write_model_folder(model, args.out)

    bgr = fixture_image()
    cv2.imwrite(str(args.out / "image.png"), bgr)
    with torch.no_grad():
        encodings, logits = (t[0].numpy().astype("<f4") for t in model(network_input(bgr)))
    encodings.tofile(args.out / "expected_box_encodings.f32")
    logits.tofile(args.out / "expected_class_logits.f32")
    found = reference_detections(encodings, logits, anc.read_sidecar(args.out / "anchors.csv"))
    check_no_near_ties(found)
    settings = {"score_threshold": SCORE_THRESHOLD, "iou_threshold": IOU_THRESHOLD, "top_k": TOP_K,
                "max_detections": MAX_DETECTIONS}
    (args.out / "expected_detections.json").write_text(  # one detection a line
        json.dumps(settings)[:-1] + ', "detections": [\n'
        + ",\n".join(json.dumps(d) for d in found) + "\n]}\n")

    # Contract breakers: a box output of 5 columns, and outputs under other names.
    wrong = TinySsd(box_channels=5).eval()
    (args.out / "wrong_box_shape").mkdir(exist_ok=True)
    export(wrong, args.out / "wrong_box_shape/model.onnx")
    (args.out / "missing_output").mkdir(exist_ok=True)
    rename_outputs(args.out / "model.onnx", args.out / "missing_output/model.onnx",
                   {"box_encodings": "boxes", "class_logits": "scores"})

    # The exported network must give PyTorch's outputs in OpenCV (what the C++ test checks too).
    net = cv2.dnn.readNetFromONNX(str(args.out / "model.onnx"))
    net.setInput(network_input(bgr).numpy())
    cv_enc, cv_log = net.forward(list(OUTPUT_NAMES))
    diff = max(np.abs(cv_enc[0] - encodings).max(), np.abs(cv_log[0] - logits).max())
    counts = {LABELS[c][1]: sum(d["class_id"] == c for d in found) for c in range(CLASSES)}
    print("wrote %s: max|OpenCV - PyTorch| = %.2e; %d reference detections %s"
          % (args.out, diff, len(found), counts))
    return 0 if diff < 1e-5 else 1


if __name__ == "__main__":
    raise SystemExit(main())
