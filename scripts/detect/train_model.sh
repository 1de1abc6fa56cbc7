#!/usr/bin/env bash
# One command from nothing to a trained detector: generate COUNT full-synthetic images with
# flexsight, cache the frozen ImageNet MobileNetV2 features, train the SSD extra layers and
# predictors, export ONNX (checked in OpenCV's DNN) with the anchors and labels beside it.
#
#   scripts/detect/train_model.sh [COUNT [RUN_DIR]] [-- train.py options]
#   scripts/detect/train_model.sh 10000 out/detect/run10k -- --epochs 30
#
# Defaults: COUNT 10000, RUN_DIR out/detect/run. The data set goes to RUN_DIR/data (kept, and
# reused when its COCO file exists), the feature cache to RUN_DIR/features (672 KB per image).
# PYTHON (default /usr/bin/python3, Debian's, which has torch) runs the training.
set -euo pipefail
cd "$(dirname "$0")/../.."

count=10000
run=out/detect/run
if [ $# -gt 0 ] && [ "$1" != "--" ]; then count=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" != "--" ]; then run=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" = "--" ]; then shift; fi
python=${PYTHON:-/usr/bin/python3}

if [ ! -x build/flexsight ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
  cmake --build build -j"$(nproc)" --target flexsight
fi
mkdir -p "$run"
if [ ! -f "$run/data/coco_instances.json" ]; then
  # Depth and masks are not needed to train boxes; the COCO file is written either way.
  build/flexsight synth full --count "$count" --no-depth --no-masks -o "$run/data"
fi
"$python" scripts/detect/train.py --data "$run/data" --out "$run" "$@"
