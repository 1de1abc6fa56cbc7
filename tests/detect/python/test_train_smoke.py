"""End to end on a tiny generated data set: flexsight synth full, feature cache, a few epochs
of training (the training loss must fall), and every output of a run."""
import csv
import json
import shutil
import unittest

from detect_test_paths import models_dir_from_argv, path_from_argv

MODELS = models_dir_from_argv()
import subprocess  # noqa: E402

from detect import train  # noqa: E402

FLEXSIGHT = path_from_argv("--flexsight")
WORK = path_from_argv("--work")


class TrainSmoke(unittest.TestCase):
    def test_run(self):
        shutil.rmtree(WORK, ignore_errors=True)
        WORK.mkdir(parents=True)
        data, run = WORK / "data", WORK / "run"
        subprocess.run([str(FLEXSIGHT), "synth", "full", "--count", "16", "--threads", "2",
                        "--no-depth", "--no-masks", "--cad", str(MODELS.parent / "cad/tless"),
                        "--backgrounds", str(MODELS.parent / "backgrounds"), "-o", str(data)],
                       check=True, stdout=subprocess.DEVNULL)
        rc = train.main(["--data", str(data), "--out", str(run), "--epochs", "4",
                         "--batch-size", "4", "--val-fraction", "0.25", "--seed", "3"])
        self.assertEqual(rc, 0)
        with open(run / "log.csv") as fh:
            rows = list(csv.DictReader(fh))
        self.assertEqual([int(r["epoch"]) for r in rows], [0, 1, 2, 3, 4])
        self.assertLess(float(rows[-1]["train_loss"]), float(rows[0]["train_loss"]))
        for name in ("model.pt", "model.onnx", "anchors.csv", "labels.txt", "loss.png",
                     "summary.json", "features/f0.npy", "features/f1.npy"):
            self.assertTrue((run / name).is_file(), name)
        summary = json.loads((run / "summary.json").read_text(),
                             parse_constant=lambda c: self.fail("summary.json holds " + c))
        self.assertEqual((summary["train_images"], summary["val_images"]), (12, 4))
        self.assertTrue(0.0 <= summary["ap50_val"] <= 1.0)
        self.assertEqual(len((run / "anchors.csv").read_text().splitlines()), 1918)
        labels = (run / "labels.txt").read_text().splitlines()
        self.assertEqual(len(labels), 24)
        self.assertEqual(labels[0], "0 0 background")
        self.assertEqual(labels[1], "1 2 obj_02")
        self.assertEqual(json.loads((run / "model.json").read_text()),
                         {"score_function": "softmax", "input_size": 300, "input_range": [-1, 1],
                          "color_order": "rgb", "box_scale": [10, 10, 5, 5]})
        # The C++ detector takes the folder as written (--score 0: every box is a candidate).
        dets = WORK / "dets.json"
        subprocess.run([str(FLEXSIGHT), "detect", str(data / "000000" / "rgb"), "--model",
                        str(run / "model.onnx"), "-o", str(dets), "--score", "0", "--quiet"],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        results = json.loads(dets.read_text())
        self.assertEqual({d["image_id"] for d in results}, set(range(1, 17)))
        category_ids = {int(line.split()[1]) for line in labels[1:]}
        self.assertTrue({d["category_id"] for d in results} <= category_ids)
        # A second run on the same images reuses the cache.
        self.assertEqual(train.main(["--data", str(data), "--out", str(run), "--epochs", "1",
                                     "--batch-size", "4", "--no-export"]), 0)
        self.check_device_option(data)

    def check_device_option(self, data):
        """--device cuda trains on a GPU where PyTorch sees one (the outputs are written from the
        CPU, so the C++ detector reads them alike) and is refused with one line where it does not."""
        import torch
        run = WORK / "run_cuda"
        args = ["--data", str(data), "--out", str(run), "--epochs", "1", "--batch-size", "4",
                "--device", "cuda"]
        if torch.cuda.is_available():
            self.assertEqual(train.main(args), 0)
            self.assertTrue((run / "model.onnx").is_file())
        else:
            self.assertEqual(train.main(args), 2)
            self.assertFalse(run.exists(), "a refused run must write nothing")


if __name__ == "__main__":
    unittest.main()
