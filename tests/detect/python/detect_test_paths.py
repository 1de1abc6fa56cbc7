"""Shared set-up of the detection Python tests: the shared model folder from the command line
(tests/CMakeLists.txt passes FLEXSIGHT_DETECTION_DATA/models). A missing model file fails the
test; it never skips. The tests import the package `detect` of scripts/, which ctest puts on
PYTHONPATH (by hand: PYTHONPATH=scripts /usr/bin/python3 tests/detect/python/test_....py)."""
import os
import sys
from pathlib import Path


def models_dir_from_argv() -> Path:
    """Pops `--models DIR` from sys.argv (before unittest parses it) and checks the files."""
    if "--models" not in sys.argv:
        sys.exit("usage: %s --models DIR [unittest options]" % sys.argv[0])
    i = sys.argv.index("--models")
    models = Path(sys.argv[i + 1])
    del sys.argv[i:i + 2]
    needed = ["ssd_mobilenetv2_oidv4/object_detection_ssd_mobilenetv2_oidv4_fp16.tflite",
              "ssd_mobilenetv2_oidv4/object_detection_oidv4_labelmap.txt",
              "mobilenet_imagenet/tf2_mobilenet_v2_1.0_224_ptq.tflite",
              "mobilenet_imagenet/mobilenet_v1_1.0_224_quant_embedding_extractor.tflite"]
    missing = [n for n in needed if not (models / n).is_file()]
    if missing:
        sys.exit("FAIL: shared model files missing under %s: %s" % (models, ", ".join(missing)))
    os.environ["FLEXSIGHT_DETECTION_MODELS"] = str(models)  # read by ssd_model at import
    return models


def path_from_argv(name: str) -> Path:
    """Pops `NAME VALUE` from sys.argv (before unittest parses it); a missing one fails."""
    if name not in sys.argv:
        sys.exit("usage: %s %s PATH ... [unittest options]" % (sys.argv[0], name))
    i = sys.argv.index(name)
    value = Path(sys.argv[i + 1])
    del sys.argv[i:i + 2]
    return value
