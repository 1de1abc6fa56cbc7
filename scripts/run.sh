#!/usr/bin/env bash
# Installs the Debian packages that are missing (scripts/setup.sh) and builds flexsight,
# then the main job: a pick on a simulated bin of our own part (scripts/pick/main_job.sh:
# the part, its templates, the bin at 1280x960, `flexsight pick`), printing the first pick
# and the time per stage and writing out/PICKS.json and out/pick.png. Every argument goes
# to `flexsight pick` (e.g. --stereo-downscale 2). Then the stereo demo on the Middlebury
# 2014 Motorcycle pair that python3-skimage ships (741x500, with ground truth): disparity,
# depth, confidence, the point cloud out/motorcycle.ply and a picture of it, bad-N against
# the ground truth. docs/quickstart.md: what each step writes and how long it takes.
set -euo pipefail
cd "$(dirname "$0")/.."
# The packages only, and only the binary the job runs: test.sh builds the rest.
scripts/setup.sh --packages-only
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target flexsight

scripts/pick/main_job.sh --out out "$@"

skimage_data=$(/usr/bin/python3 -c 'import os, skimage.data; print(os.path.dirname(skimage.data.__file__))')
# The ground truth ships as a NumPy archive; convert it to PFM (inf = unknown).
/usr/bin/python3 scripts/stereo/npz_to_pfm.py "$skimage_data/motorcycle_disp.npz" out/motorcycle_gt.pfm

# Its calibration, from the documentation skimage ships with it.
/usr/bin/python3 scripts/stereo/skimage_motorcycle_calib.py out/motorcycle_calib.txt

# ndisp 70: the disparity range Middlebury gives for this scene at this resolution.
# Besides the disparity: depth (mm), confidence, and the colored point cloud with normals
# and its picture.
echo "stereo demo: the Middlebury 2014 Motorcycle pair"
build/flexsight stereo "$skimage_data/motorcycle_left.png" "$skimage_data/motorcycle_right.png" \
  -o out/motorcycle_disp.pfm --png out/motorcycle_disp.png --ndisp 70 \
  --calib out/motorcycle_calib.txt --depth out/motorcycle_depth.pfm \
  --conf out/motorcycle_conf.pfm --conf-png out/motorcycle_conf.png \
  --ply out/motorcycle.ply --render out/motorcycle_cloud.png \
  --gt out/motorcycle_gt.pfm
