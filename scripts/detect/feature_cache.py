"""The frozen feature extractor's output cached on disk for detect.train: with the extractor frozen,
its feature maps (or the frozen stem's output, with --tune-from) are computed once per image and
read back every epoch."""

from __future__ import annotations

import hashlib
import json
import time
from pathlib import Path

import numpy as np
import torch

from .coco_set import CocoSet
from .ssd_model import MODELS_DIR, SSDMobileNetV2

CL = torch.channels_last  # NHWC: PyTorch's CPU convolutions (oneDNN) run ~2x faster in it
FEATURE_RATE = []  # images/s of the last feature caching, for summary.json


def cache_key(data: CocoSet, backbone: str, image_size: int, tune_from: int) -> str:
    h = hashlib.sha256()
    h.update(("%s %d %s %d\n" % (backbone, image_size, MODELS_DIR, tune_from)).encode())
    for im in data.images:
        st = (data.root / im["file_name"]).stat()
        h.update(("%s %d %d\n" % (im["file_name"], st.st_size, int(st.st_mtime))).encode())
    return h.hexdigest()[:16]


def cache_features(model: SSDMobileNetV2, data: CocoSet, cache_dir: Path, key: str,
                   tune_from: int, batch: int = 16, device: str = "cpu"):
    """Float16 memmaps, channels last (the layout the channels-last layers read without a copy):
    with the whole extractor frozen its two feature maps [N, 19, 19, 576] and [N, 10, 10, 1280];
    with blocks from tune_from on trained, the frozen stem's output (e.g. [N, 19, 19, 96] for
    block 13). Reused when the key (images, backbone, split point) matches, recomputed otherwise."""
    cache_dir.mkdir(parents=True, exist_ok=True)
    meta = cache_dir / "cache.json"
    bb = model.backbone
    if tune_from < 0:
        shapes = [(len(data), s, s, c) for c, s in zip(bb.feature_channels, bb.feature_sizes)]
        paths = [cache_dir / "f0.npy", cache_dir / "f1.npy"]
        compute = bb
    else:
        size, channels = bb.stem_shape(tune_from)
        shapes = [(len(data), size, size, channels)]
        paths = [cache_dir / ("stem%d.npy" % tune_from)]
        compute = lambda x: (bb.stem(x, tune_from),)  # noqa: E731
    if meta.exists() and json.loads(meta.read_text()).get("key") == key:
        maps = [np.load(p, mmap_mode="r") for p in paths]
        if all(m.shape == s for m, s in zip(maps, shapes)):
            print("features: reusing the cache in %s" % cache_dir)
            return maps
    meta.unlink(missing_ok=True)
    maps = [np.lib.format.open_memmap(p, mode="w+", dtype=np.float16, shape=s)
            for p, s in zip(paths, shapes)]
    bb.eval()
    t0, c0, n = time.time(), time.process_time(), len(data)
    with torch.no_grad():
        for start in range(0, n, batch):
            idx = range(start, min(start + batch, n))
            x = data.images_tensor(idx, model.image_size).contiguous(memory_format=CL).to(device)
            for m, f in zip(maps, compute(x)):
                m[start:start + len(idx)] = f.permute(0, 2, 3, 1).half().cpu().numpy()
            done = start + len(idx)
            if done == n or (start // batch) % 10 == 0:
                print("features: %d/%d images, %.1f images/s" % (done, n, done / (time.time() - t0)),
                      flush=True)
    for m in maps:
        m.flush()
    meta.write_text(json.dumps({"key": key, "count": n}))
    wall, cpu = time.time() - t0, time.process_time() - c0
    FEATURE_RATE[:] = [n / wall]
    print("features: cached %d images in %.1f s: %.1f images/s, %.2f CPU s per image; %.0f MB"
          % (n, wall, n / wall, cpu / n, sum(p.stat().st_size for p in paths) / 1e6))
    return [np.load(p, mmap_mode="r") for p in paths]
