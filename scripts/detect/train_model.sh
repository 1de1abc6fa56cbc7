#!/usr/bin/env bash
# One command from nothing to a trained detector: split the background photographs into a
# training and a held-out part, generate COUNT full-synthetic training images and TEST_COUNT
# test images (another seed, the held-out backgrounds), cache the frozen part of the ImageNet
# MobileNetV2, train, export ONNX (checked in OpenCV's DNN) with anchors.csv, labels.txt and
# model.json beside it, and score the held-out test set.
#
#   scripts/detect/train_model.sh [COUNT [RUN_DIR]] [-- detect.train options]
#   scripts/detect/train_model.sh 20000 out/detect/ship -- --tune-from 13 --epochs 2
#
# Defaults: COUNT 20000, RUN_DIR out/detect/run, TEST_COUNT 1000 (environment), seed 1 for the
# training images and 2 for the test images. Data sets are kept and reused when their COCO file
# exists; the feature cache goes to RUN_DIR/features. PYTHON (default /usr/bin/python3, Debian's,
# which has torch) runs the training. The shipped model's exact command is in
# models/tless-ssd/README.md.
set -euo pipefail
cd "$(dirname "$0")/../.."

count=20000
run=out/detect/run
if [ $# -gt 0 ] && [ "$1" != "--" ]; then count=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" != "--" ]; then run=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" = "--" ]; then shift; fi
python=${PYTHON:-/usr/bin/python3}
test_count=${TEST_COUNT:-1000}
backgrounds=${FLEXSIGHT_DETECTION_DATA:-../shared/detection}/backgrounds

if [ ! -x build/flexsight ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
  cmake --build build -j"$(nproc)" --target flexsight
fi
mkdir -p "$run"
scripts/detect/split_backgrounds.sh "$backgrounds" "$run/backgrounds"
# Depth and masks are not needed to train boxes; the COCO file is written either way.
if [ ! -f "$run/data/coco_instances.json" ]; then
  build/flexsight synth full --count "$count" --seed 1 --no-depth --no-masks \
    --backgrounds "$run/backgrounds/train" -o "$run/data"
fi
if [ ! -f "$run/test/coco_instances.json" ]; then
  build/flexsight synth full --count "$test_count" --seed 2 --no-depth --no-masks \
    --backgrounds "$run/backgrounds/test" -o "$run/test"
fi
PYTHONPATH=scripts "$python" -m detect.train --data "$run/data" --test "$run/test" --out "$run" "$@"
