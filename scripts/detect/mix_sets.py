"""One COCO-instances folder from several (a `flexsight synth full` set, bin tiles from
detect.bin_tiles, ...), for training mixes: each image keeps its source's name in `source`,
which detect.train --sources selects by, so that every mix trains from one feature cache.

    python3 -m detect.mix_sets -o OUT NAME=DIR[:COUNT] ...      # from scripts/

DIR/coco_instances.json is read; COUNT takes its first COUNT images (by id; default all).
OUT/NAME is a symbolic link to DIR, file names become NAME/<file_name>; image and annotation
ids are renumbered in the order given. The sources must have the same categories.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path


def parse_source(text: str):
    name, sep, rest = text.partition("=")
    if not sep or not name or "/" in name:
        raise ValueError("%s: not NAME=DIR[:COUNT]" % text)
    folder, _, count = rest.partition(":")
    if count and not count.isdigit():
        raise ValueError("%s: COUNT %s is not a number" % (text, count))
    coco = Path(folder) / "coco_instances.json"
    if not coco.is_file():
        raise ValueError("%s: %s is missing" % (text, coco))
    return name, Path(folder), int(count) if count else 0


def mix(sources, out: Path) -> dict:
    images, annotations, categories = [], [], None
    for name, folder, count in sources:
        coco = json.loads((folder / "coco_instances.json").read_text())
        cats = sorted(coco["categories"], key=lambda c: c["id"])
        if categories is None:
            categories = cats
        elif [c["id"] for c in cats] != [c["id"] for c in categories]:
            raise ValueError("%s: other categories than the first source" % folder)
        chosen = sorted(coco["images"], key=lambda im: im["id"])
        chosen = chosen[:count] if count else chosen
        new_id = {}
        for im in chosen:
            new_id[im["id"]] = len(images)
            images.append(dict(im, id=len(images), file_name="%s/%s" % (name, im["file_name"]),
                               source=name))
        for a in coco["annotations"]:
            if a["image_id"] in new_id:
                annotations.append(dict(a, id=len(annotations), image_id=new_id[a["image_id"]]))
    return {"images": images, "annotations": annotations, "categories": categories}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-o", "--out", type=Path, required=True, help="the folder to make (must not exist)")
    ap.add_argument("sources", nargs="+", help="NAME=DIR[:COUNT]")
    args = ap.parse_args(argv)
    try:
        if args.out.exists():
            raise ValueError("-o %s: exists already" % args.out)
        sources = [parse_source(s) for s in args.sources]
        if len({s[0] for s in sources}) != len(sources):
            raise ValueError("a NAME given twice")
        coco = mix(sources, args.out)
    except ValueError as e:
        print("error: %s" % e, file=sys.stderr)
        return 1
    args.out.mkdir(parents=True)
    for name, folder, _ in sources:
        os.symlink(folder.resolve(), args.out / name)
    (args.out / "coco_instances.json").write_text(json.dumps(coco) + "\n")
    counts = {}
    for im in coco["images"]:
        counts[im["source"]] = counts.get(im["source"], 0) + 1
    print("mix_sets: %s -> %s" % (", ".join("%s %d" % kv for kv in counts.items()), args.out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
