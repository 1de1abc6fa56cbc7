"""Train SSD-MobileNetV2 on a COCO-instances data set from `flexsight synth` by transfer learning.

Default (the paper's set-up): the ImageNet MobileNetV2 feature extractor is frozen, so its two
feature maps are computed once per image and cached on disk (float16 memmaps, 672 KB per image),
then only the extra layers and the box/class predictors are trained, many epochs, fast.
--train-all trains every layer from the images instead (no cache; far slower on a CPU).
With the cache no augmentation can happen here: the generator already draws flips, rotation,
blur and noise per image, so diversity comes from generating more images.

Loss (the original SSD's): smooth L1 on the encoded boxes of matched anchors (IoU >= 0.5, plus the
best anchor of every ground-truth box) and softmax cross-entropy with hard-negative mining at
3 negatives per positive, both divided by the number of positives.

Writes into --out: model.pt (checkpoint), model.onnx (checked in cv2.dnn when importable),
anchors.csv, labels.txt, model.json (score function, input size and range, box scale), log.csv,
loss.png, summary.json (timings, losses, AP@0.5 of the
validation images and of as many training images).

    python3 -m detect.train --data DIR --out RUN --epochs 30     # from scripts/
    python3 -m detect.train --data DIR --out RUN --device cuda   # the same on a GPU
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import random
import sys
import time
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F
from PIL import Image

from . import anchors as anc
from .coco_set import CocoSet
from .detect_eval import average_precision_50, decode_detections
from .export_onnx import check_with_opencv, export
from .feature_cache import CL, FEATURE_RATE, cache_features, cache_key
from .ssd_model import FEATURE_BLOCK, build_model, load_onnx_weights

NEG_POS_RATIO = 3
MIN_NEGATIVES = 8  # per image, so that images without parts still teach background


# ----------------------------------------------------------------------------------------------
# Data

IGNORED = -1  # label of anchors on a crowd region (a part mostly hidden or cut by a tile)


def match_all(data: CocoSet, anchors: np.ndarray):
    """Labels and box targets per anchor; background anchors overlapping a crowd region at
    IoU >= 0.5 are IGNORED, so that half a part teaches neither part nor background."""
    labels = np.zeros((len(data), len(anchors)), np.int64)
    targets = np.zeros((len(data), len(anchors), 4), np.float32)
    corners = anc.corners(anchors)
    for i, (boxes, cls) in enumerate(data.gt):
        labels[i], targets[i] = anc.match(boxes, cls, anchors)
        if len(data.crowds[i]):
            on_crowd = anc.iou(corners, data.crowds[i]).max(1) >= 0.5
            labels[i][on_crowd & (labels[i] == 0)] = IGNORED
    return torch.from_numpy(labels), torch.from_numpy(targets)


# ----------------------------------------------------------------------------------------------
# Loss

def ssd_loss(boxes, logits, labels, targets):
    """Returns (localisation, classification), each summed and divided by the positives."""
    pos = labels > 0
    num_pos = pos.sum(1)
    n = num_pos.sum().clamp(min=1).float()
    loc = F.smooth_l1_loss(boxes[pos], targets[pos], reduction="sum", beta=1.0) / n
    ce = F.cross_entropy(logits.reshape(-1, logits.shape[-1]), labels.reshape(-1),
                         reduction="none", ignore_index=IGNORED).view(labels.shape)
    neg_loss = ce.detach().masked_fill(pos | (labels == IGNORED), -1.0)
    rank = neg_loss.argsort(1, descending=True).argsort(1)
    num_neg = (NEG_POS_RATIO * num_pos).clamp(min=MIN_NEGATIVES, max=labels.shape[1] - 1)
    neg = (rank < num_neg[:, None]) & (labels != IGNORED)
    cls = (ce * (pos | neg)).sum() / n
    return loc, cls


# ----------------------------------------------------------------------------------------------
# Training

def seed_everything(seed: int) -> None:
    random.seed(seed)
    np.random.seed(seed)
    torch.manual_seed(seed)


def split(n: int, val_fraction: float, seed: int):
    perm = np.random.RandomState(seed).permutation(n)
    nv = max(1, int(round(n * val_fraction))) if n > 1 and val_fraction > 0 else 0
    return np.sort(perm[nv:]), np.sort(perm[:nv])


def batch_inputs(args, model, data, feats, idx):
    if feats is None:
        return data.images_tensor(idx, model.image_size).contiguous(memory_format=CL).to(args.device)
    # NHWC float16 on disk -> NCHW float32 tensors with channels-last strides, no copy but the cast.
    return tuple(torch.from_numpy(f[idx]).to(args.device).float().permute(0, 3, 1, 2) for f in feats)


def forward(model, inputs, args):
    if args.train_all:
        return model(inputs)
    if args.tune_from >= 0:
        if args.backbone_lr_factor == 0:  # the whole extractor frozen, run from a stem cache
            with torch.no_grad():
                features = model.backbone.tail(inputs[0], args.tune_from)
            return model.detector(*features)
        return model.detector(*model.backbone.tail(inputs[0], args.tune_from))
    return model.detector(*inputs)


def evaluate(args, model, data, feats, labels, targets, idx):
    model.eval()
    tot = np.zeros(2)
    with torch.no_grad():
        for s in range(0, len(idx), args.batch_size):
            b = idx[s:s + args.batch_size]
            out = forward(model, batch_inputs(args, model, data, feats, b), args)
            loc, cls = ssd_loss(*out, labels[b].to(args.device), targets[b].to(args.device))
            tot += np.array([loc.item(), cls.item()]) * len(b)
    return tot / max(len(idx), 1)


def average_precision(args, model, data, feats, idx, per_class: bool = False):
    """AP@0.5 (detect_eval) of the model on the images idx; with feats None the whole network
    runs on the images (held-out test sets have no cache)."""
    anchors = anc.generate()
    model.eval()
    dets = []
    with torch.no_grad():
        for s in range(0, len(idx), args.batch_size):
            b = idx[s:s + args.batch_size]
            if feats is None:
                boxes, logits = model(data.images_tensor(b, model.image_size)
                                      .contiguous(memory_format=CL).to(args.device))
            else:
                boxes, logits = forward(model, batch_inputs(args, model, data, feats, b), args)
            dets += [decode_detections(x.cpu().numpy(), y.cpu().numpy(), anchors)
                     for x, y in zip(boxes, logits)]
    result = average_precision_50(dets, [data.gt[i] for i in idx], model.detector.num_classes)
    return result if per_class else result[0]


def finite_or_null(v):
    """Plain JSON: NaN (no value, e.g. the speed of epoch 0) becomes null, numpy scalars float."""
    if isinstance(v, dict):
        return {k: finite_or_null(x) for k, x in v.items()}
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(v) else None
    return v


def plot(log_rows, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ep = [r["epoch"] for r in log_rows]
    fig, (ax, ax_ap) = plt.subplots(1, 2, figsize=(10, 4))
    ap_rows = [r for r in log_rows if r.get("val_ap50") == r.get("val_ap50")]
    ax_ap.plot([r["epoch"] for r in ap_rows], [r["val_ap50"] for r in ap_rows], "s-",
               color="C1", label="validation")
    ax_ap.set_xlabel("epoch")
    ax_ap.set_ylabel("mAP@0.5 (VOC all-point)")
    ax_ap.set_ylim(0, 1)
    ax_ap.grid(True, alpha=0.3)
    ax_ap.legend()
    ax.plot(ep, [r["train_loss"] for r in log_rows], "o-", label="train")
    if any(r["val_loss"] == r["val_loss"] for r in log_rows):
        ax.plot(ep, [r["val_loss"] for r in log_rows], "s-", label="validation")
    ax.set_xlabel("epoch")
    ax.set_ylabel("SSD loss (smooth L1 + cross-entropy)")
    ax.set_yscale("log")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def write_model_json(path: Path, image_size: int = 300) -> None:
    """model.json: what the C++ detector (host/detect/detector_model.h) must know about the model
    that the ONNX graph does not say. Scores by softmax because the loss is softmax
    cross-entropy (the C++ post-processing's own default is the TF OD API's sigmoid); the input
    is RGB scaled to [-1, 1]; boxes are encoded with the scale factors 10, 10, 5, 5."""
    settings = {"score_function": "softmax", "input_size": image_size, "input_range": [-1, 1],
                "color_order": "rgb", "box_scale": [int(s) for s in anc.SCALE_FACTORS]}
    path.write_text(json.dumps(settings, indent=1) + "\n")


def write_outputs(model, data, out: Path) -> None:
    anc.write_sidecar(out / "anchors.csv")
    lines = ["0 0 background"] + ["%d %d %s" % (i + 1, c["id"], c.get("name", c["id"]))
                                  for i, c in enumerate(data.categories)]
    (out / "labels.txt").write_text("\n".join(lines) + "\n")
    write_model_json(out / "model.json", model.image_size)
    export(model, out / "model.onnx")
    try:
        import cv2  # noqa: F401
    except ImportError:
        print("onnx: wrote %s; cv2 is not importable, not checked in OpenCV" % (out / "model.onnx"))
        return
    rgb = np.asarray(Image.open(data.path(0)).convert("RGB"))
    diff = check_with_opencv(model, out / "model.onnx", rgb)
    print("onnx: wrote %s; cv2.dnn reads it, max|OpenCV - PyTorch| = %.2e" % (out / "model.onnx", diff))
    if diff > 1e-3:
        raise RuntimeError("OpenCV's forward differs from PyTorch's by %.2e" % diff)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", type=Path, required=True,
                    help="folder written by `flexsight synth` (reads DATA/coco_instances.json)")
    ap.add_argument("--out", type=Path, required=True, help="run folder for the outputs")
    ap.add_argument("--cache", type=Path, help="feature cache folder (default OUT/features)")
    ap.add_argument("--epochs", type=int, default=30)
    ap.add_argument("--batch-size", type=int, default=32)
    ap.add_argument("--lr", type=float, default=1e-3, help="peak learning rate (Adam)")
    ap.add_argument("--weight-decay", type=float, default=4e-5)
    ap.add_argument("--val-fraction", type=float, default=0.1)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=2, help="torch CPU threads")
    ap.add_argument("--max-minutes", type=float, default=0,
                    help="stop after the epoch that passes this long (0: no limit); the number of"
                         " epochs then depends on the machine: --stop-epoch repeats a run exactly")
    ap.add_argument("--max-images", type=int, default=0,
                    help="train on this many images in all, stopping within an epoch (the"
                         " learning-rate schedule ends there; 0: --epochs whole epochs): the same"
                         " budget for training mixes of different sizes")
    ap.add_argument("--stop-epoch", type=int, default=0,
                    help="stop after this epoch, the learning-rate schedule still that of --epochs"
                         " (0: run them all)")
    ap.add_argument("--backbone", choices=("imagenet", "oidv4"), default="imagenet",
                    help="feature extractor weights: ImageNet MobileNetV2 (the paper) or the"
                         " OIDv4 detector's")
    ap.add_argument("--class-heads", choices=("random", "oidv4"), default="random")
    ap.add_argument("--train-all", action="store_true",
                    help="train the feature extractor too, from images, without the cache")
    ap.add_argument("--tune-from", type=int, default=-1, metavar="BLOCK",
                    help="train the extractor's blocks from BLOCK (0-16) on, and conv1, caching the"
                         " frozen blocks' output; -1 (default) freezes the whole extractor")
    ap.add_argument("--backbone-lr-factor", type=float, default=0.1,
                    help="learning rate of trained extractor layers relative to --lr")
    ap.add_argument("--limit", type=int, default=0, help="use only the first N images (0: all)")
    ap.add_argument("--train-limit", type=int, default=0,
                    help="train on the first N images of the training split only (0: all); the"
                         " validation split and the cache stay those of the whole data set, so"
                         " data-size experiments share one cache")
    ap.add_argument("--sources", default="",
                    help="train and validate only on the images whose `source` (detect.mix_sets)"
                         " is in this comma-separated list; the cache stays the whole set's")
    ap.add_argument("--init-onnx", type=Path,
                    help="start from the weights of a model this script exported (e.g."
                         " models/tless-ssd/model.onnx) instead of the TFLite models: fine-tuning")
    ap.add_argument("--test", type=Path,
                    help="held-out data set folder (coco_instances.json): AP@0.5 per class at the end")
    ap.add_argument("--ap-images", type=int, default=500,
                    help="validation images scored for the mAP curve after every epoch (0: none)")
    ap.add_argument("--no-export", action="store_true", help="skip the ONNX export at the end")
    ap.add_argument("--device", choices=("cpu", "cuda"), default="cpu",
                    help="where the network runs (feature caching, training, AP); the outputs are "
                         "written from the CPU either way")
    args = ap.parse_args(argv)
    if args.device == "cuda" and not torch.cuda.is_available():
        print("error: --device cuda: this PyTorch sees no CUDA device", file=sys.stderr)
        return 2

    seed_everything(args.seed)
    torch.set_num_threads(args.threads)
    coco_path = args.data / "coco_instances.json"
    if not coco_path.exists():
        print("error: %s does not exist" % coco_path, file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    data = CocoSet(coco_path, args.limit)
    print("data: %d images, %d boxes, %d categories from %s"
          % (len(data), sum(len(g[1]) for g in data.gt), len(data.categories), coco_path))
    model = build_model(len(data.categories), args.backbone, args.class_heads)
    if args.init_onnx:
        load_onnx_weights(model, args.init_onnx)
        print("weights: from %s" % args.init_onnx)
    model = model.to(device=args.device, memory_format=CL)
    anchors = anc.generate()
    labels, targets = match_all(data, anchors)
    print("matching: %.1f positive anchors per image" % (labels > 0).sum(1).float().mean())
    train_idx, val_idx = split(len(data), args.val_fraction, args.seed)
    if args.sources:
        wanted = set(args.sources.split(","))
        keep = np.array([s in wanted for s in data.sources])
        if not keep.any():
            print("error: --sources %s: no image of %s has one of them" % (args.sources, coco_path),
                  file=sys.stderr)
            return 2
        train_idx, val_idx = train_idx[keep[train_idx]], val_idx[keep[val_idx]]
    if args.train_limit:
        train_idx = train_idx[:args.train_limit]
    print("split: %d training, %d validation images" % (len(train_idx), len(val_idx)))

    if args.train_all:
        feats = None
        args.tune_from = -1
        params = [{"params": model.backbone.parameters(), "lr": args.lr * args.backbone_lr_factor},
                  {"params": model.detector.parameters(), "lr": args.lr}]
    else:
        if not -1 <= args.tune_from <= FEATURE_BLOCK:
            print("error: --tune-from must be in [-1, %d]" % FEATURE_BLOCK, file=sys.stderr)
            return 2
        key = cache_key(data, args.backbone, model.image_size, args.tune_from)
        feats = cache_features(model, data, args.cache or args.out / "features", key,
                               args.tune_from, device=args.device)
        for p in model.backbone.parameters():
            p.requires_grad_(False)
        params = [{"params": model.detector.parameters(), "lr": args.lr}]
        if args.tune_from >= 0 and args.backbone_lr_factor > 0:
            tuned = [p for b in model.backbone.blocks[args.tune_from:] for p in b.parameters()]
            tuned += list(model.backbone.conv1.parameters())
            for p in tuned:
                p.requires_grad_(True)
            params.append({"params": tuned, "lr": args.lr * args.backbone_lr_factor})
    opt = torch.optim.AdamW(params, lr=args.lr, weight_decay=args.weight_decay)
    steps_per_epoch = max(1, math.ceil(len(train_idx) / args.batch_size))
    total = steps_per_epoch * args.epochs
    if args.max_images:
        total = max(1, math.ceil(args.max_images / args.batch_size))
        args.epochs = math.ceil(total / steps_per_epoch)
    warmup = max(1, min(total // 20, 200))
    base = [g["lr"] for g in opt.param_groups]

    rng = np.random.RandomState(args.seed)
    log_rows, step, t_start, c_start = [], 0, time.time(), time.process_time()
    # Epoch 0: the losses of the starting point (training loss on at most 256 images).
    tr0 = evaluate(args, model, data, feats, labels, targets, train_idx[:256])
    va0 = evaluate(args, model, data, feats, labels, targets, val_idx) if len(val_idx) else [math.nan] * 2
    ap_idx = val_idx[:args.ap_images]

    def val_ap():
        return average_precision(args, model, data, feats, ap_idx) if len(ap_idx) else math.nan

    log_rows.append({"epoch": 0, "train_loss": float(np.sum(tr0)), "train_loc": tr0[0],
                     "train_cls": tr0[1], "val_loss": float(np.sum(va0)), "val_loc": va0[0],
                     "val_cls": va0[1], "val_ap50": val_ap(), "images_per_s": math.nan,
                     "elapsed_s": 0.0})
    print("epoch   0: train %.3f (loc %.3f cls %.3f)  val %.3f (loc %.3f cls %.3f)  before training"
          % (log_rows[0]["train_loss"], tr0[0], tr0[1], log_rows[0]["val_loss"], va0[0], va0[1]))
    images_trained, train_time = 0, 0.0
    for epoch in range(1, args.epochs + 1):
        model.train()
        if not args.train_all:
            model.backbone.eval()
        perm = rng.permutation(train_idx)
        sums, seen, t_epoch = np.zeros(2), 0, time.time()
        for s in range(0, len(perm), args.batch_size):
            if step >= total:  # --max-images reached within the epoch
                break
            b = np.sort(perm[s:s + args.batch_size])  # sorted: memmap reads in file order
            f = min(1.0, (step + 1) / warmup) * 0.5 * (1 + math.cos(math.pi * step / total))
            for g, lr in zip(opt.param_groups, base):
                g["lr"] = lr * f
            out = forward(model, batch_inputs(args, model, data, feats, b), args)
            loc, cls = ssd_loss(*out, labels[b].to(args.device), targets[b].to(args.device))
            loss = loc + cls
            opt.zero_grad()
            loss.backward()
            opt.step()
            sums += np.array([loc.item(), cls.item()]) * len(b)
            seen += len(b)
            step += 1
            if (args.train_all or args.tune_from >= 0) and step % 20 == 0:
                print("  step %d: loss %.3f (%.1f images/s)"
                      % (step, loss.item(), seen / (time.time() - t_epoch)), flush=True)
        dt = time.time() - t_epoch
        images_trained += seen
        train_time += dt
        tr = sums / max(seen, 1)
        va = evaluate(args, model, data, feats, labels, targets, val_idx) if len(val_idx) else [math.nan] * 2
        row = {"epoch": epoch, "train_loss": tr.sum(), "train_loc": tr[0], "train_cls": tr[1],
               "val_loss": float(np.sum(va)), "val_loc": va[0], "val_cls": va[1],
               "val_ap50": val_ap(), "images_per_s": seen / dt, "elapsed_s": time.time() - t_start}
        log_rows.append(row)
        print("epoch %3d: train %.3f (loc %.3f cls %.3f)  val %.3f (loc %.3f cls %.3f)  AP@0.5 %.3f  "
              "%.0f images/s  %.0f s" % (epoch, row["train_loss"], tr[0], tr[1], row["val_loss"],
                                         va[0], va[1], row["val_ap50"], row["images_per_s"],
                                         row["elapsed_s"]),
              flush=True)
        plot(log_rows, args.out / "loss.png")
        if args.max_minutes and time.time() - t_start > args.max_minutes * 60:
            print("stopping: --max-minutes %.1f reached" % args.max_minutes)
            break
        if args.stop_epoch and epoch >= args.stop_epoch:
            print("stopping: --stop-epoch %d reached" % args.stop_epoch)
            break

    with open(args.out / "log.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(log_rows[0].keys()))
        w.writeheader()
        w.writerows(log_rows)
    plot(log_rows, args.out / "loss.png")
    print("training: %d steps, %.1f images/s, %.3f CPU s per image (validation included), loss %.3f -> %.3f"
          " (validation %.3f -> %.3f)"
          % (step, images_trained / max(train_time, 1e-9),
             (time.process_time() - c_start) / max(images_trained, 1), log_rows[0]["train_loss"],
             log_rows[-1]["train_loss"], log_rows[0]["val_loss"], log_rows[-1]["val_loss"]))
    ap_train = average_precision(args, model, data, feats, train_idx[:len(val_idx) or 200])
    ap_val = average_precision(args, model, data, feats, val_idx) if len(val_idx) else math.nan
    print("AP@0.5: validation %.3f, training %.3f (%d images each at most)"
          % (ap_val, ap_train, len(val_idx) or 200))
    summary = {"images": len(data), "train_images": len(train_idx), "val_images": len(val_idx),
               "epochs": log_rows[-1]["epoch"], "steps": step,
               "train_images_per_s": images_trained / max(train_time, 1e-9),
               "first": log_rows[0], "last": log_rows[-1], "ap50_val": ap_val, "ap50_train": ap_train,
               "settings": {k: str(v) for k, v in vars(args).items()}}
    if feats is not None and FEATURE_RATE:
        summary["feature_cache_images_per_s"] = FEATURE_RATE[0]
    if args.test:
        test = CocoSet(args.test / "coco_instances.json")
        if [c["id"] for c in test.categories] != [c["id"] for c in data.categories]:
            raise ValueError("%s has other categories than the training data" % args.test)
        m, per_class = average_precision(args, model, test, None, np.arange(len(test)), True)
        names = [c.get("name", str(c["id"])) for c in data.categories]
        summary["test"] = {"data": str(args.test), "images": len(test), "ap50": m,
                           "ap50_per_class": {names[c - 1]: v for c, v in per_class.items()}}
        print("AP@0.5 on the held-out test set (%d images): %.3f" % (len(test), m))
    (args.out / "summary.json").write_text(json.dumps(finite_or_null(summary), indent=1) + "\n")
    model = model.eval().to(device="cpu", memory_format=torch.contiguous_format)
    torch.save({"model": model.state_dict(), "num_classes": model.detector.num_classes,
                "categories": data.categories, "args": {k: str(v) for k, v in vars(args).items()}},
               args.out / "model.pt")
    if not args.no_export:
        write_outputs(model, data, args.out)
    print("wrote %s" % args.out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
