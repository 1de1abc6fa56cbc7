#!/usr/bin/env bash
# Installs whatever is missing from Debian packages, then builds FlexSight into build/.
# Runs as root, or as a user who may sudo. Safe to run again: installs only what lacks.
# `--no-build`: the packages and build/venv, no build (scripts/test.sh --sanitize, which
# builds into build-asan/); `--packages-only`: the packages alone (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config git
  libopencv-dev libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd clinfo
  libembree-dev nlohmann-json3-dev libceres-dev libnanoflann-dev libbullet-dev libcpp-httplib-dev
  python3 python3-venv python3-numpy python3-pil python3-skimage python3-meshio python3-matplotlib
  python3-torch python3-torchvision python3-opencv python3-flatbuffers python3-onnx python3-requests
  clang libclang-rt-14-dev libomp-dev
)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi

# pycocotools, for the check that COCO's own reader reads our COCO files
# (tests/dataset/coco_pycocotools_check.py), is on PyPI only. It goes into a venv in the
# build folder (PEP 668 keeps pip out of Debian's Python) made from Debian's python3, so
# that --system-site-packages gives it Debian's numpy and PIL. Made once: re-made only
# when pycocotools does not import. CMake's FLEXSIGHT_COCO_PYTHON points at it.
[ "${1:-}" = --packages-only ] && exit 0
venv=build/venv
if ! "$venv/bin/python3" -c "import pycocotools" 2>/dev/null; then
  echo "setup: installing pycocotools into $venv"
  /usr/bin/python3 -m venv --system-site-packages "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check pycocotools==2.0.11
fi

[ "${1:-}" = --no-build ] && exit 0

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
