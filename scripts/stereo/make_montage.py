#!/usr/bin/python3
"""One picture of a benchmark run: per scene, the left image, then each method's colored
disparity and error map (green = within 2 px, yellow to red = worse, magenta = no
result, black = no ground truth), halved and labelled.

usage: make_montage.py DATA_DIR OUT.jpg SCENE[,SCENE...] LABEL=RUN_DIR [LABEL=RUN_DIR ...]

scripts/stereo/region_report.py builds its pictures with tile() and sheet().
"""
import os
import sys

from PIL import Image, ImageDraw


def tile(source, scale=0.5, width=None):
    """An image (a path or a PIL image) as RGB, scaled by `scale` or to `width` pixels."""
    image = (Image.open(source) if isinstance(source, str) else source).convert("RGB")
    if width is not None:
        scale = width / image.width
    return image.resize((int(image.width * scale), int(image.height * scale)))


def sheet(rows):
    """rows: [(scene, [(label, image), ...]), ...] -> one image, a row per scene, each
    tile under a "scene: label" line."""
    width = max(sum(image.width for _, image in row) for _, row in rows)
    height = sum(max(image.height for _, image in row) + 16 for _, row in rows)
    canvas = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(canvas)
    y = 0
    for scene, row in rows:
        x = 0
        for label, image in row:
            draw.text((x + 2, y + 2), f"{scene}: {label}", fill="black")
            canvas.paste(image, (x, y + 16))
            x += image.width
        y += max(image.height for _, image in row) + 16
    return canvas


def save(image, target, **options):
    """Written under a temporary name first, so that a reader never sees half a file."""
    base, extension = os.path.splitext(target)
    temporary = base + ".tmp" + extension
    image.save(temporary, **options)
    os.replace(temporary, target)


def main():
    if len(sys.argv) < 5:
        raise SystemExit(__doc__)
    data, target, scenes = sys.argv[1], sys.argv[2], sys.argv[3].split(",")
    runs = [argument.split("=", 1) for argument in sys.argv[4:]]
    rows = []
    for scene in scenes:
        row = [("left image", tile(os.path.join(data, scene, "im0.png")))]
        for label, folder in runs:
            row.append((f"{label} disparity", tile(os.path.join(folder, f"{scene}_disp.png"))))
            row.append((f"{label} error", tile(os.path.join(folder, f"{scene}_error.png"))))
        rows.append((scene, row))
    save(sheet(rows), target, quality=85)


if __name__ == "__main__":
    main()
