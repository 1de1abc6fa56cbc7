"""Check the PyTorch port of the shared TFLite models.

1. The complete OIDv4 SSD-MobileNetV2 (fp16 weights) in PyTorch against the TFLite interpreter
   (tflite-runtime from PyPI, when importable) on photographs: max abs difference of the raw
   box encodings and class logits.
2. The ImageNet MobileNetV2 (int8 per channel) as a feature extractor, completed with its own
   classifier at 224x224, against the quantised TFLite model: same top-1 class, top-5 overlap.
3. Without an interpreter, and in any case: the OIDv4 detections decoded with the anchors on the
   photographs, printed with their Open Images labels (plausibility by eye).

Run with a Python that has torch and, for 1 and 2, tflite_runtime (e.g. a venv made with
--system-site-packages from Debian's python3, plus `pip install tflite-runtime==2.14.0`).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import torch
from PIL import Image

from . import anchors as anc
from .ssd_model import (MOBILENET_V2_IMAGENET, SSD_OIDV4, MobileNetV2Features, SSDMobileNetV2,
                       _conv_ops, load_backbone_from_tflite, load_detector_from_tflite, preprocess)
from .tflite_reader import TfliteModel

DEFAULT_IMAGES = ("val_101085.jpg", "train_65019.jpg", "train_187029.jpg", "val_3096.jpg",
                  "train_100075.jpg", "val_38082.jpg")


def interpreter(path):
    try:
        from tflite_runtime.interpreter import Interpreter
    except ImportError:
        return None
    it = Interpreter(model_path=str(path), num_threads=1)
    it.allocate_tensors()
    return it


def run_tflite(it, x_nhwc):
    it.set_tensor(it.get_input_details()[0]["index"], x_nhwc)
    it.invoke()
    return [it.get_tensor(o["index"]) for o in it.get_output_details()]


def check_oidv4(images, it) -> bool:
    model = SSDMobileNetV2(num_classes=23).eval()
    load_detector_from_tflite(model, SSD_OIDV4, class_heads=True, backbone=True)
    labels = (SSD_OIDV4.parent / "object_detection_oidv4_labelmap.txt").read_text().splitlines()
    anchors = anc.generate()
    ok = True
    for path in images:
        rgb = np.asarray(Image.open(path).convert("RGB"))
        x = preprocess(rgb)
        with torch.no_grad():
            boxes, logits = (t[0].numpy() for t in model(x))
        if it is not None:
            tb, tc = run_tflite(it, np.ascontiguousarray(x.numpy().transpose(0, 2, 3, 1)))
            db, dc = np.abs(boxes - tb[0]).max(), np.abs(logits - tc[0]).max()
            print("OIDv4 %s: max|PyTorch - TFLite| box_encodings %.2e, class_logits %.2e"
                  " (ranges %.1f, %.1f)" % (path.name, db, dc, np.ptp(tb), np.ptp(tc)))
            ok &= bool(db < 1e-3 and dc < 1e-3)
        # Scores: sigmoid (the TF OD API score converter of this model); background column out.
        scores = 1 / (1 + np.exp(-logits[:, 1:]))
        decoded = anc.corners(anc.decode(boxes, anchors))
        best = np.argsort(-scores.max(1))
        shown, kept = 0, []
        for i in best:
            if scores[i].max() < 0.3 or shown >= 5:
                break
            if kept and anc.iou(decoded[i:i + 1], decoded[kept]).max() > 0.5:
                continue
            kept.append(i)
            shown += 1
            c = int(scores[i].argmax())
            y0, x0, y1, x1 = np.clip(decoded[i], 0, 1)
            print("    %-18s %.2f  box (x %.2f-%.2f, y %.2f-%.2f)"
                  % (labels[c + 1], scores[i, c], x0, x1, y0, y1))
        if not shown:
            print("    no detection above 0.3")
    return ok


class ImagenetClassifier(torch.nn.Module):
    """MobileNetV2 features + the TFLite graph's own head (mean pool, 1x1 conv to 1001)."""

    def __init__(self, tfl: TfliteModel):
        super().__init__()
        self.features = MobileNetV2Features(224)
        head = _conv_ops(tfl)[-1]
        w = tfl.array(tfl.tensors[head.inputs[1]])
        self.fc = torch.nn.Linear(w.shape[-1], w.shape[0])
        self.fc.weight.data = torch.from_numpy(w.reshape(w.shape[0], -1))
        self.fc.bias.data = torch.from_numpy(tfl.array(tfl.tensors[head.inputs[2]]))

    def forward(self, x):
        return torch.softmax(self.fc(self.features(x)[1].mean((2, 3))), 1)


def check_imagenet(images, it) -> bool:
    tfl = TfliteModel.read(MOBILENET_V2_IMAGENET)
    net = ImagenetClassifier(tfl).eval()
    holder = SSDMobileNetV2()
    holder.backbone = net.features
    load_backbone_from_tflite(holder, MOBILENET_V2_IMAGENET)
    names = [n.split(",")[0] for n in
             (MOBILENET_V2_IMAGENET.parent / "imagenet_labels.txt").read_text().splitlines()]
    ok = True
    for path in images:
        rgb = np.asarray(Image.open(path).convert("RGB").resize((224, 224), Image.BILINEAR))
        q = rgb.astype(np.uint8)[None]
        # TFLite input: uint8 with scale 1/127.5 and zero point 127, i.e. about x/127.5 - 1.
        x = torch.from_numpy((q.astype(np.float32) - 127.0) / 127.5).permute(0, 3, 1, 2)
        with torch.no_grad():
            p = net(x)[0].numpy()
        top = np.argsort(-p)[:5]
        line = "ImageNet %s: PyTorch top-1 %s (%.2f)" % (path.name, names[top[0]], p[top[0]])
        if it is not None:
            (tq,) = run_tflite(it, q)
            tp = tq[0].astype(np.float32) / 256.0
            ttop = np.argsort(-tp)[:5]
            overlap = len(set(top) & set(ttop))
            line += "; TFLite int8 top-1 %s (%.2f); top-5 overlap %d/5; max|dp| %.3f" % (
                names[ttop[0]], tp[ttop[0]], overlap, np.abs(p - tp).max())
            ok &= bool(top[0] == ttop[0] or p[ttop[0]] > 0.5 * p[top[0]])
        print(line)
    return ok


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--backgrounds", type=Path,
                    default=SSD_OIDV4.parents[2] / "backgrounds",
                    help="folder of photographs (default: the shared BSDS500 backgrounds)")
    ap.add_argument("--images", nargs="*", default=list(DEFAULT_IMAGES))
    args = ap.parse_args(argv)
    images = [args.backgrounds / n for n in args.images]
    missing = [str(p) for p in images if not p.exists()]
    if missing:
        print("missing images: " + ", ".join(missing), file=sys.stderr)
        return 2
    it_oid, it_imagenet = interpreter(SSD_OIDV4), interpreter(MOBILENET_V2_IMAGENET)
    if it_oid is None:
        print("tflite_runtime is not importable: self-consistency checks only")
    ok = check_oidv4(images, it_oid)
    ok &= check_imagenet(images, it_imagenet)
    print("port check: %s" % ("PASS" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
