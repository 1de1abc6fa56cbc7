#!/usr/bin/env bash
# Runs on the lent GPU machine, from the repository root, with .device/ carried there
# (scripts/stereo/device_bundle.sh made it). Probes for NVIDIA's OpenCL driver, points the
# OpenCL loader at it, then times the matcher on every scene through OpenCL and
# compares its bytes with the reference path run on the same machine, then again with
# one pixel per work item (FLEXSIGHT_CL_LANES=1). Everything it finds goes to $OUT:
# probe.txt, device_check.md, device_check_lanes1.md and lanes1_cmp.txt,
# device_check_fast.md (the fast preset), the profiles and the disparities (disp.tar.gz
# and fast.tar.gz, to score here with `flexsight eval DATA --results DIR`).
# usage (through the device tool): scripts/stereo/device_run.sh [REPEAT [SCENE ...]]
# (SCENEs: a subset of the bundle's, e.g. for a rehearsal on PoCL here)
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-/tmp/flexsight_device_out}
repeat=${1:-5}
shift $(( $# > 0 ? 1 : 0 ))
mkdir -p "$out"
{
  echo "## probe $(date -u +%FT%TZ)"
  uname -a
  ldd --version 2>&1 | head -1
  nvidia-smi -L 2>&1 || echo "nvidia-smi: not found"
  echo "-- /etc/OpenCL/vendors:"; ls -l /etc/OpenCL/vendors 2>&1
  echo "-- NVIDIA OpenCL libraries:"
  find / -xdev \( -name 'libnvidia-opencl.so*' -o -name 'libOpenCL.so*' \) 2>/dev/null | sort
} > "$out/probe.txt" 2>&1
# ocl-icd (carried as .device/lib/libOpenCL.so.1) reads the vendors folder; when no
# entry there names NVIDIA's driver, a folder with the machine's entries plus one naming
# the driver's library by full path is made (containers often mount the library only).
icd_lib=$(find / -xdev -name 'libnvidia-opencl.so.1' 2>/dev/null | head -1)
if ! grep -qs nvidia /etc/OpenCL/vendors/*.icd && [ -n "$icd_lib" ]; then
  mkdir -p .device/icd
  cp /etc/OpenCL/vendors/*.icd .device/icd/ 2>/dev/null
  echo "$icd_lib" > .device/icd/nvidia.icd
  export OCL_ICD_VENDORS=$PWD/.device/icd
  echo "-- made .device/icd/nvidia.icd -> $icd_lib" >> "$out/probe.txt"
fi
export LD_LIBRARY_PATH=$PWD/.device/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
scenes=$(mktemp -d)
if [ $# -gt 0 ]; then
  for name in "$@"; do grep "^$name " .device/scenes/manifest.txt; done > "$scenes/manifest.txt"
else
  cp .device/scenes/manifest.txt "$scenes/"
fi
while read -r _ left right _; do
  for f in "$left" "$right"; do gunzip -c ".device/scenes/$f.gz" > "$scenes/$f"; done
done < "$scenes/manifest.txt"
mkdir -p "$out/disp"
cat "$out/probe.txt"
.device/bin/flexsight_device_check "$scenes/manifest.txt" "$out/disp" --repeat "$repeat" \
  2>&1 | tee "$out/device_check.md"
status=${PIPESTATUS[0]}
# The same scenes with one pixel per work item (FLEXSIGHT_CL_LANES=1, the kernels' GPU
# setting; the default 8 lanes suit CPU drivers), no reference run: its disparities must
# be the default's bytes, which cmp checks.
mkdir -p "$scenes/lanes1"
FLEXSIGHT_CL_LANES=1 .device/bin/flexsight_device_check "$scenes/manifest.txt" "$scenes/lanes1" \
  --repeat "$repeat" --reference 0 2>&1 | tee "$out/device_check_lanes1.md"
compared=0
for f in "$out"/disp/*.pfm; do
  compared=$((compared + 1))
  cmp -s "$f" "$scenes/lanes1/$(basename "$f")" || echo "lanes 1 differs: $(basename "$f")"
done > "$out/lanes1_cmp.txt"
echo "lanes 1 against 8: $compared disparities compared" >> "$out/lanes1_cmp.txt"
cat "$out/lanes1_cmp.txt"
# The fast preset (flexsight --preset fast) with the GPU setting, timed only: its
# disparities come back to be scored here (fast.tar.gz), to compare with PoCL's score
# of the same preset (fast_preset() in host/stereo/stereo_params.cpp).
mkdir -p "$out/fast"
FLEXSIGHT_CL_LANES=1 .device/bin/flexsight_device_check "$scenes/manifest.txt" "$out/fast" \
  --repeat "$repeat" --reference 0 --preset fast 2>&1 | tee "$out/device_check_fast.md"
tar -C "$out" -czf "$out/fast.tar.gz" fast && rm -rf "$out/fast"
# Where the time goes on this device: one profiled run of three scenes (device time per
# kernel from OpenCL events; profiling adds its own overhead, so not the timings above).
head -3 "$scenes/manifest.txt" > "$scenes/profile.txt"
mkdir -p "$scenes/profile_out"
.device/bin/flexsight_device_check "$scenes/profile.txt" "$scenes/profile_out" --repeat 1 \
  --reference 0 --profile 2>&1 | tee "$out/device_profile.md"
FLEXSIGHT_CL_LANES=1 .device/bin/flexsight_device_check "$scenes/profile.txt" \
  "$scenes/profile_out" --repeat 1 --reference 0 --profile 2>&1 |
  tee "$out/device_profile_lanes1.md"
tar -C "$out" -czf "$out/disp.tar.gz" disp && rm -rf "$out/disp"
exit "$status"
