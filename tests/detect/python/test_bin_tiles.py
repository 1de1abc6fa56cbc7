"""detect.bin_tiles and detect.mix_sets on a tiny bin made by `flexsight synth bin`: the tiles
are pick's, the boxes are the visible masks' inside each tile, parts below the visible share
are crowd regions that detect.train leaves out of both part and background, the output
repeats with its seed, and bad input is refused before anything is written."""
import json
import shutil
import subprocess
import sys
import unittest
from pathlib import Path

import numpy as np
from PIL import Image

from detect import bin_tiles, mix_sets, train
from detect import anchors as anc
from detect.coco_set import CocoSet


def pop_arg(name: str) -> Path:
    i = sys.argv.index(name)
    value = Path(sys.argv[i + 1])
    del sys.argv[i:i + 2]
    return value


FLEXSIGHT = pop_arg("--flexsight")
WORK = pop_arg("--work")
BIN = WORK / "bins" / "bin000"
MIN_VISIBLE = 0.9  # a sparse bin hides few parts by half; at 0.9 its view has crowd regions


def setUpModule():
    shutil.rmtree(WORK, ignore_errors=True)
    WORK.mkdir(parents=True)
    subprocess.run([str(FLEXSIGHT), "synth", "bin", "--count", "1", "--size", "320x240",
                    "--seed", "9", "-o", str(WORK / "bins")],
                   check=True, stdout=subprocess.DEVNULL)


def run_tiles(out, *options):
    return bin_tiles.main([str(WORK / "bins"), "-o", str(out), "--tile", "128",
                           "--min-visible", str(MIN_VISIBLE), *options])


class BinTiles(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = WORK / "tiles"
        assert run_tiles(cls.out, "--shifts", "1", "--seed", "3") == 0
        cls.coco = json.loads((cls.out / "coco_instances.json").read_text())

    def test_tiles_are_picks_grid(self):
        # fixed_tiling(128) over 320 x 240: stride 96, starts spread evenly, last at the edge.
        self.assertEqual(bin_tiles.tile_starts(320, 128, 96), [0, 96, 192])
        self.assertEqual(bin_tiles.tile_starts(240, 128, 96), [0, 56, 112])
        self.assertEqual(bin_tiles.tile_starts(1280, 256, 192), [0, 171, 341, 512, 683, 853, 1024])
        grid0 = [im["rect"] for im in self.coco["images"] if "_s0_" in im["file_name"]]
        self.assertEqual(grid0, [[x, y, 128, 128] for y in (0, 56, 112) for x in (0, 96, 192)])
        shifted = [im["rect"] for im in self.coco["images"] if "_s1_" in im["file_name"]]
        self.assertTrue(shifted and shifted != grid0)
        for x, y, w, h in shifted:
            self.assertTrue(0 <= x <= 320 - 128 and 0 <= y <= 240 - 128 and w == h == 128)

    def test_boxes_are_the_visible_masks_in_the_tile(self):
        info = json.loads((BIN / "scene_gt_info.json").read_text())["0"]
        view = np.asarray(Image.open(BIN / "rgb" / "000000.png").convert("RGB"))
        whole = [a for a in self.coco["annotations"] if a["image_id"] == 0]
        # The whole view: every visible part, its box the BOP bbox_visib, crowd below MIN_VISIBLE.
        visible = [i for i in info if i["px_count_visib"] > 0]
        self.assertEqual(len(whole), len(visible))
        for a, i in zip(whole, visible):
            self.assertEqual(a["bbox"], i["bbox_visib"])
            self.assertEqual(a["iscrowd"], int(i["visib_fract"] < MIN_VISIBLE))
        self.assertTrue(any(a["iscrowd"] for a in whole), "a bin hides some parts")
        images = {im["id"]: im for im in self.coco["images"]}
        for a in self.coco["annotations"]:
            im = images[a["image_id"]]
            x, y, w, h = a["bbox"]
            self.assertTrue(0 <= x and 0 <= y and x + w <= im["width"] and y + h <= im["height"])
            self.assertEqual(a["iscrowd"], int(a["visib_fract"] < MIN_VISIBLE))
        # A tile's picture is the view's pixels under its rect.
        tile = self.coco["images"][3]
        x, y, w, h = tile["rect"]
        np.testing.assert_array_equal(
            np.asarray(Image.open(self.out / tile["file_name"]).convert("RGB")), view[y:y + h, x:x + w])
        # A part cut by a tile keeps less of itself there than in the whole view.
        share = {}
        for a in self.coco["annotations"]:
            share.setdefault(a["category_id"], []).append(a["visib_fract"])
        self.assertTrue(any(min(v) < max(v) for v in share.values()))

    def test_repeats_with_its_seed(self):
        again = WORK / "tiles_again"
        shutil.rmtree(again, ignore_errors=True)
        self.assertEqual(run_tiles(again, "--shifts", "1", "--seed", "3"), 0)
        self.assertEqual((again / "coco_instances.json").read_bytes(),
                         (self.out / "coco_instances.json").read_bytes())
        other = WORK / "tiles_seed4"
        shutil.rmtree(other, ignore_errors=True)
        self.assertEqual(run_tiles(other, "--shifts", "1", "--seed", "4"), 0)
        self.assertNotEqual((other / "coco_instances.json").read_bytes(),
                            (self.out / "coco_instances.json").read_bytes())

    def test_crowd_regions_are_neither_part_nor_background(self):
        data = CocoSet(self.out / "coco_instances.json")
        labels, _ = train.match_all(data, anc.generate())
        self.assertGreater(int((labels == train.IGNORED).sum()), 0)
        self.assertGreater(int((labels > 0).sum()), 0)
        # The loss leaves ignored anchors out: changing their logits changes nothing.
        import torch
        torch.manual_seed(0)
        b = labels[:4]
        boxes, logits = torch.zeros(4, b.shape[1], 4), torch.randn(4, b.shape[1], 24)
        tweaked = logits.clone()
        tweaked[b == train.IGNORED] += 5.0
        self.assertEqual(train.ssd_loss(boxes, logits, b, boxes)[1].item(),
                         train.ssd_loss(boxes, tweaked, b, boxes)[1].item())

    def test_mix_keeps_sources(self):
        out = WORK / "mix"
        shutil.rmtree(out, ignore_errors=True)
        self.assertEqual(mix_sets.main(["-o", str(out), "a=%s:3" % self.out, "b=%s" % self.out]), 0)
        data = CocoSet(out / "coco_instances.json")
        self.assertEqual(data.sources, ["a"] * 3 + ["b"] * len(self.coco["images"]))
        self.assertTrue(data.path(4).is_file())
        self.assertEqual(len(data.gt[3][1]), len(CocoSet(self.out / "coco_instances.json").gt[0][1]))

    def test_bad_input_writes_nothing(self):
        out = WORK / "bad"
        shutil.rmtree(out, ignore_errors=True)
        self.assertEqual(bin_tiles.main([str(WORK / "bins"), "-o", str(out), "--tile", "256"]), 1)
        self.assertFalse(out.exists())
        self.assertEqual(bin_tiles.main([str(WORK), "-o", str(out)]), 1)
        self.assertFalse(out.exists())
        self.assertEqual(mix_sets.main(["-o", str(out), "a=%s" % (WORK / "nothing")]), 1)
        self.assertFalse(out.exists())


if __name__ == "__main__":
    unittest.main()
