#!/usr/bin/python3
"""One picture of a benchmark run: per scene, the left image, then each method's colored
disparity and error map (green = within 2 px, yellow to red = worse, magenta = no
result, black = no ground truth), halved and labelled.

usage: make_montage.py DATA_DIR OUT.jpg SCENE[,SCENE...] LABEL=RUN_DIR [LABEL=RUN_DIR ...]
"""
import os
import sys

from PIL import Image, ImageDraw


def tile(path, scale=0.5):
    image = Image.open(path).convert("RGB")
    return image.resize((int(image.width * scale), int(image.height * scale)))


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
    width = max(sum(image.width for _, image in row) for _, row in rows)
    height = sum(max(image.height for _, image in row) + 16 for _, row in rows)
    sheet = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(sheet)
    y = 0
    for scene, row in rows:
        x = 0
        for label, image in row:
            draw.text((x + 2, y + 2), f"{scene}: {label}", fill="black")
            sheet.paste(image, (x, y + 16))
            x += image.width
        y += max(image.height for _, image in row) + 16
    temporary = target + ".tmp.jpg"
    sheet.save(temporary, quality=85)
    os.replace(temporary, target)


if __name__ == "__main__":
    main()
