#!/usr/bin/env bash
# docs/images/synth_examples.jpg: four full-synthetic and four semi-synthetic images
# with their boxes (the contact sheets of two small runs, one row each).
#   scripts/synth/make_readme_picture.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
flexsight="$root/build/flexsight"
"$flexsight" synth full --count 4 --seed 3 -o "$work/full"
FLEXSIGHT="$flexsight" "$root/scripts/synth/demo_semi.sh" "$work/demo" 4
/usr/bin/python3 - "$work/full/contact_sheet.png" "$work/demo/semi/contact_sheet.png" \
  "$root/docs/images/synth_examples.jpg" <<'PY'
import sys
from PIL import Image, ImageDraw
rows = [Image.open(p).convert("RGB") for p in sys.argv[1:3]]
label_width = 28
sheet = Image.new("RGB", (max(r.width for r in rows) + label_width, sum(r.height for r in rows)), "white")
draw = ImageDraw.Draw(sheet)
y = 0
for row, label in zip(rows, ["full", "semi"]):
    sheet.paste(row, (label_width, y))
    text = Image.new("RGB", (row.height, label_width), "white")
    ImageDraw.Draw(text).text((row.height // 2 - 12, 8), label, fill="black")
    sheet.paste(text.rotate(90, expand=True), (0, y))
    y += row.height
sheet.save(sys.argv[3], quality=85)
PY
echo "wrote docs/images/synth_examples.jpg"
