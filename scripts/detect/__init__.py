"""The part detector's Python side as one package, `detect`: run its modules from scripts/ (or
with scripts/ on PYTHONPATH) as `python3 -m detect.train`, `python3 -m detect.export_onnx`, ...

Imports go one way: anchors and tflite_reader need nothing of the package; ssd_model reads
them; export_onnx builds on ssd_model; coco_set is the data; detect_eval decodes and scores
(its command line evaluates a checkpoint, so it reads coco_set and export_onnx);
feature_cache reads coco_set and ssd_model; train uses all of these; make_fixture_model and
verify_port sit on top.
"""
