#!/usr/bin/env bash
# Splits a folder of background photographs into OUT/train and OUT/test (symbolic links):
# every sixth file in name order goes to test, so that a detector is measured on images whose
# backgrounds it never saw. Deterministic; rerunning rebuilds the two folders.
#
#   scripts/detect/split_backgrounds.sh BACKGROUNDS_DIR OUT_DIR
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 BACKGROUNDS_DIR OUT_DIR" >&2
  exit 2
fi
src=$(cd "$1" && pwd)
out=$2
rm -rf "$out/train" "$out/test"
mkdir -p "$out/train" "$out/test"
i=0
while IFS= read -r name; do
  if [ $((i % 6)) -eq 5 ]; then part=test; else part=train; fi
  ln -s "$src/$name" "$out/$part/$name"
  i=$((i + 1))
done < <(cd "$src" && find . -maxdepth 1 -type f \( -iname '*.jpg' -o -iname '*.jpeg' -o -iname '*.png' \) \
           -printf '%f\n' | LC_ALL=C sort)
if [ "$i" -lt 6 ]; then
  echo "error: $src holds $i pictures; at least 6 are needed to keep some for testing" >&2
  exit 1
fi
echo "backgrounds: $(ls "$out/train" | wc -l) for training, $(ls "$out/test" | wc -l) for testing, in $out"
