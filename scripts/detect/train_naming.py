"""Train the part namer: a small CNN that names the part in a detector's box (host/detect/part_namer.h).

Input: the grey square crop of naming_data.py (SIZE x SIZE), standardised per crop
((x / 255 - mean) / (std + 0.02), so the part's grey level and the exposure do not name it);
output: one logit per class of the detector's labels (softmax). Augmented per batch: contrast,
brightness and gamma, noise, and a corner of another crop pasted over it (a neighbour in the bin).

Writes into --out: model.onnx (opset 11, checked in cv2.dnn against PyTorch), labels.txt
(the detector's format: "0 0 background", then one line per output), model.json, model.pt, log.csv, curve.png,
summary.json (accuracy top-1/3/5 of validation and --test sets).

    python3 -m detect.train_naming --train train.npz --test test.npz --out RUN --epochs 12   # from scripts/
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import time
from pathlib import Path

import numpy as np
import torch
import torch.nn as nn
import torch.nn.functional as F

STD_FLOOR = 0.02  # of the [0, 1] range: a flat crop is not blown up to noise


def standardise(x: torch.Tensor) -> torch.Tensor:
    """uint8-valued crops [N, 1, S, S] as float, each to zero mean and unit spread."""
    x = x / 255.0
    mean = x.mean(dim=(1, 2, 3), keepdim=True)
    std = x.std(dim=(1, 2, 3), keepdim=True, unbiased=False)
    return (x - mean) / (std + STD_FLOOR)


def conv(cin: int, cout: int, stride: int = 1) -> nn.Sequential:
    return nn.Sequential(nn.Conv2d(cin, cout, 3, stride, 1, bias=False), nn.BatchNorm2d(cout), nn.ReLU(inplace=True))


class NamingNet(nn.Module):
    """Four stages of 3x3 convolutions halving the crop, global average pool, one linear layer."""

    def __init__(self, classes: int, width: int = 16):
        super().__init__()
        w = width
        self.features = nn.Sequential(
            conv(1, w, 2), conv(w, w),                  # S/2
            conv(w, 2 * w, 2), conv(2 * w, 2 * w),      # S/4
            conv(2 * w, 4 * w, 2), conv(4 * w, 4 * w),  # S/8
            conv(4 * w, 8 * w, 2), conv(8 * w, 8 * w),  # S/16
        )
        self.dropout = nn.Dropout(0.2)
        self.classifier = nn.Linear(8 * w, classes)

    def forward(self, x):
        x = self.features(x)
        x = F.adaptive_avg_pool2d(x, 1).flatten(1)
        return self.classifier(self.dropout(x))


def augment(x: torch.Tensor, g: torch.Generator) -> torch.Tensor:
    """x: float [N, 1, S, S] in 0..255; returns the same range."""
    n, _, s, _ = x.shape
    u = lambda *shape: torch.rand(*shape, generator=g)
    gamma = torch.exp((u(n, 1, 1, 1) - 0.5) * 0.8)
    x = 255.0 * (x / 255.0).clamp(0, 1) ** gamma
    x = x * (0.6 + 0.8 * u(n, 1, 1, 1)) + (u(n, 1, 1, 1) - 0.5) * 60.0
    x = x + torch.randn(x.shape, generator=g) * (u(n, 1, 1, 1) * 8.0)
    # A neighbour's corner over a third of the crops: partial occlusion by another part.
    other = x[torch.randperm(n, generator=g)]
    h = (s * (0.25 + 0.3 * u(n, 1, 1, 1))).long()
    w = (s * (0.25 + 0.3 * u(n, 1, 1, 1))).long()
    rows = torch.arange(s).view(1, 1, s, 1)
    cols = torch.arange(s).view(1, 1, 1, s)
    from_top, from_left = u(n, 1, 1, 1) < 0.5, u(n, 1, 1, 1) < 0.5
    in_rows = torch.where(from_top, rows < h, rows >= s - h)
    in_cols = torch.where(from_left, cols < w, cols >= s - w)
    pasted = in_rows & in_cols & (u(n, 1, 1, 1) < 0.33)
    x = torch.where(pasted, other, x)
    return x.clamp(0, 255)


def topk_accuracy(logits: torch.Tensor, y: torch.Tensor, ks=(1, 3, 5)) -> dict:
    order = logits.argsort(dim=1, descending=True)
    return {f"top{k}": float((order[:, :k] == y[:, None]).any(dim=1).float().mean()) for k in ks}


@torch.no_grad()
def predict(model: nn.Module, x_uint8: np.ndarray, device, batch: int = 512) -> torch.Tensor:
    model.eval()
    out = []
    for i in range(0, len(x_uint8), batch):
        xb = torch.from_numpy(x_uint8[i:i + batch]).float()[:, None].to(device)
        out.append(model(standardise(xb)).cpu())
    return torch.cat(out) if out else torch.zeros(0)


def export_onnx(model: nn.Module, size: int, path: Path) -> None:
    model = model.cpu().eval()
    torch.onnx.export(model, torch.zeros(1, 1, size, size), str(path), opset_version=11,
                      input_names=["crop"], output_names=["logits"], do_constant_folding=True)


def check_with_opencv(model: nn.Module, path: Path, x: np.ndarray) -> float:
    """Largest logit difference between cv2.dnn and PyTorch on a few crops."""
    import cv2
    net = cv2.dnn.readNetFromONNX(str(path))
    blob = standardise(torch.from_numpy(x).float()[:, None]).numpy()
    diff = 0.0
    ref = model.cpu().eval()(torch.from_numpy(blob)).detach().numpy()
    for i in range(len(blob)):
        net.setInput(blob[i:i + 1])
        diff = max(diff, float(np.abs(net.forward() - ref[i:i + 1]).max()))
    return diff


def plot_curve(rows: list[dict], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    e = [r["epoch"] for r in rows]
    fig, ax = plt.subplots(1, 2, figsize=(8, 3), dpi=80)
    ax[0].plot(e[1:], [r["train_loss"] for r in rows[1:]], label="training")
    ax[0].plot(e, [r["val_loss"] for r in rows], label="validation")
    ax[0].set_xlabel("epoch"), ax[0].set_ylabel("cross-entropy"), ax[0].legend()
    for k in ("top1", "top3", "top5"):
        ax[1].plot(e, [r[f"val_{k}"] for r in rows], label=k.replace("top", "top-"))
    ax[1].set_xlabel("epoch"), ax[1].set_ylabel("validation accuracy"), ax[1].set_ylim(0, 1), ax[1].legend()
    fig.tight_layout()
    fig.savefig(path)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--train", type=Path, action="append", required=True,
                   help="naming_data.py crops (jittered); several are joined")
    p.add_argument("--test", type=Path, action="append", default=[], help="held-out crops, reported at the end")
    p.add_argument("--out", type=Path, required=True)
    p.add_argument("--epochs", type=int, default=12)
    p.add_argument("--batch", type=int, default=128)
    p.add_argument("--lr", type=float, default=3e-3)
    p.add_argument("--width", type=int, default=16, help="channels of the first stage (x2 per stage)")
    p.add_argument("--val-share", type=float, default=0.08)
    p.add_argument("--max-crops", type=int, default=0, help="train on this many crops at most (0: all)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--device", default="cpu", choices=["cpu", "cuda"])
    p.add_argument("--threads", type=int, default=2, help="CPU threads (torch.set_num_threads)")
    p.add_argument("--max-minutes", type=float, default=60.0, help="stop after the epoch that passes this")
    a = p.parse_args()
    torch.set_num_threads(a.threads)
    torch.manual_seed(a.seed)
    device = torch.device(a.device)
    a.out.mkdir(parents=True, exist_ok=True)

    sets = [np.load(path) for path in a.train]
    x_all = np.concatenate([d["x"] for d in sets])
    y_all = np.concatenate([d["y"] for d in sets])
    ids = [int(c) for c in sets[0]["category_ids"]]
    if any([int(c) for c in d["category_ids"]] != ids for d in sets):
        raise SystemExit("error: --train sets of different parts")
    size = x_all.shape[1]
    order = np.random.default_rng(a.seed).permutation(len(y_all))
    n_val = int(len(y_all) * a.val_share)
    val_idx, train_idx = order[:n_val], order[n_val:]
    if a.max_crops > 0:
        train_idx = train_idx[:a.max_crops]
    x_val, y_val = x_all[val_idx], torch.from_numpy(y_all[val_idx])
    x_train = torch.from_numpy(x_all[train_idx])
    y_train = torch.from_numpy(y_all[train_idx])

    model = NamingNet(len(ids), a.width).to(device)
    params = sum(p.numel() for p in model.parameters())
    opt = torch.optim.AdamW(model.parameters(), lr=a.lr, weight_decay=1e-4)
    steps = a.epochs * math.ceil(len(y_train) / a.batch)
    sched = torch.optim.lr_scheduler.OneCycleLR(opt, max_lr=a.lr, total_steps=steps, pct_start=0.15)
    g = torch.Generator().manual_seed(a.seed)
    rows = []

    def validate(epoch: int, train_loss: float, seconds: float) -> None:
        logits = predict(model, x_val, device)
        row = {"epoch": epoch, "train_loss": train_loss, "val_loss": float(F.cross_entropy(logits, y_val)),
               "seconds": seconds, **{f"val_{k}": v for k, v in topk_accuracy(logits, y_val).items()}}
        rows.append(row)
        print(f"epoch {epoch}: train {train_loss:.3f} val {row['val_loss']:.3f} top-1 {row['val_top1']:.3f} "
              f"top-3 {row['val_top3']:.3f} top-5 {row['val_top5']:.3f} ({seconds:.0f} s)", flush=True)

    print(f"{len(y_train)} training crops, {n_val} validation, {size}x{size}, {params} parameters", flush=True)
    start = time.time()
    validate(0, float("nan"), 0.0)
    for epoch in range(1, a.epochs + 1):
        model.train()
        perm = torch.randperm(len(y_train), generator=g)
        total, count = 0.0, 0
        for i in range(0, len(perm), a.batch):
            idx = perm[i:i + a.batch]
            xb = augment(x_train[idx].float()[:, None], g)
            xb, yb = standardise(xb).to(device), y_train[idx].to(device)
            loss = F.cross_entropy(model(xb), yb, label_smoothing=0.05)
            opt.zero_grad()
            loss.backward()
            opt.step()
            sched.step()
            total += float(loss) * len(idx)
            count += len(idx)
        validate(epoch, total / count, time.time() - start)
        export_onnx(model, size, a.out / "model.onnx")  # a stopped run leaves its last epoch
        model.to(device)
        if (time.time() - start) / 60.0 > a.max_minutes:
            print(f"stopped after epoch {epoch}: --max-minutes {a.max_minutes}")
            break

    model = model.cpu().eval()
    torch.save({"state_dict": model.state_dict(), "width": a.width, "size": size, "category_ids": ids}, a.out / "model.pt")
    export_onnx(model, size, a.out / "model.onnx")
    diff = check_with_opencv(model, a.out / "model.onnx", x_val[:16])
    (a.out / "labels.txt").write_text("0 0 background\n" + "".join(f"{i + 1} {c} obj_{c:02d}\n" for i, c in enumerate(ids)))
    (a.out / "model.json").write_text(json.dumps({
        "task": "naming", "input_size": size, "color_order": "grey", "margin": 0.15,
        "normalisation": "per_crop_standardise", "std_floor": STD_FLOOR}, indent=1) + "\n")
    with open(a.out / "log.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader(), w.writerows(rows)
    plot_curve(rows, a.out / "curve.png")
    summary = {"parameters": params, "train_crops": len(y_train), "val_crops": n_val, "size": size,
               "epochs": rows[-1]["epoch"], "minutes": (time.time() - start) / 60.0, "opencv_max_logit_diff": diff,
               "validation": {k: rows[-1][f"val_{k}"] for k in ("top1", "top3", "top5")}, "tests": {}}
    for path in a.test:
        t = np.load(path)
        summary["tests"][str(path)] = topk_accuracy(predict(model, t["x"], "cpu"), torch.from_numpy(t["y"]))
        summary["tests"][str(path)]["crops"] = int(len(t["y"]))
    (a.out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    print(json.dumps(summary, indent=1))


if __name__ == "__main__":
    main()
