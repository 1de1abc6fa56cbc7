#!/usr/bin/env bash
# The main job on data every Debian machine can get: the Middlebury 2014 Motorcycle pair
# that python3-skimage ships (741x500, with ground truth). Writes out/motorcycle_disp.pfm
# and a colored PNG, depth, confidence, the point cloud out/motorcycle.ply and a picture
# of it, and prints time per stage and bad-N against the ground truth. Then the part
# detector on eight held-out synthetic images, scored against their ground truth.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh

skimage_data=$(/usr/bin/python3 -c 'import os, skimage.data; print(os.path.dirname(skimage.data.__file__))')
mkdir -p out
# The ground truth ships as a NumPy archive; convert it to PFM (inf = unknown).
/usr/bin/python3 scripts/stereo/npz_to_pfm.py "$skimage_data/motorcycle_disp.npz" out/motorcycle_gt.pfm

# Its calibration, from the documentation skimage ships with it.
/usr/bin/python3 scripts/stereo/skimage_motorcycle_calib.py out/motorcycle_calib.txt

# ndisp 70: the disparity range Middlebury gives for this scene at this resolution.
# Besides the disparity: depth (mm), confidence, and the colored point cloud with normals
# and its picture.
build/flexsight stereo "$skimage_data/motorcycle_left.png" "$skimage_data/motorcycle_right.png" \
  -o out/motorcycle_disp.pfm --png out/motorcycle_disp.png --ndisp 70 \
  --calib out/motorcycle_calib.txt --depth out/motorcycle_depth.pfm \
  --conf out/motorcycle_conf.pfm --conf-png out/motorcycle_conf.png \
  --ply out/motorcycle.ply --render out/motorcycle_cloud.png \
  --gt out/motorcycle_gt.pfm "$@"

# The part detector (the shipped model, models/tless-ssd) on eight held-out synthetic
# images of the T-LESS parts: boxes as COCO results and a picture, then its scores
# against their ground truth (out/detect_eval/report.md, pr_curve.png, montage.jpg).
build/flexsight detect tests/data/detect/tless_synth_8/000000/rgb \
  -o out/detections.json --png out/detections.png --quiet
build/flexsight eval-det tests/data/detect/tless_synth_8 --out out/detect_eval --overwrite --quiet
