"""SSD-MobileNetV2 300x300 in PyTorch, laid out as the TF Object Detection API builds it, with
TensorFlow SAME padding, and its weights loaded from TFLite flatbuffers.

    model = SSDMobileNetV2(num_classes=23)
    load_backbone_from_tflite(model, MOBILENET_V2_IMAGENET)       # ImageNet feature extractor
    load_detector_from_tflite(model, SSD_OIDV4, class_heads=False)  # extra layers, box heads
    box_encodings, class_logits = model(x)   # x: [B, 3, 300, 300] RGB in [-1, 1]

Structure: `model.backbone` (MobileNetV2 up to Conv_1) returns the two feature maps the TF OD API
predicts from: layer_15/expansion_output (576 channels, 19x19: the ReLU6 output of block 13's
expansion) and layer_19 (1280 channels, 10x10). `model.detector` holds the four extra layers
(1x1 bottleneck then 3x3 stride-2 convolution, ReLU6; 512, 256, 256, 128 channels) and six
1x1 box and class predictors; it maps the two feature maps to (box_encodings [B, 1917, 4],
class_logits [B, 1917, num_classes + 1]), so that training can run it on cached features.
Batch norm is folded into the convolutions, as in the TFLite files: every convolution has a bias.
"""
from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import torch
from torch import nn

from .anchors import anchors_per_cell
from .tflite_reader import TfliteModel

MODELS_DIR = Path(os.environ.get("FLEXSIGHT_DETECTION_MODELS",
                                 Path(__file__).resolve().parents[3] / "shared/detection/models"))
MOBILENET_V2_IMAGENET = MODELS_DIR / "mobilenet_imagenet/tf2_mobilenet_v2_1.0_224_ptq.tflite"
SSD_OIDV4 = MODELS_DIR / "ssd_mobilenetv2_oidv4/object_detection_ssd_mobilenetv2_oidv4_fp16.tflite"

# MobileNetV2 1.0 inverted residual blocks: (expansion t, output channels c, repeats n, stride s).
BLOCKS = ((1, 16, 1, 1), (6, 24, 2, 2), (6, 32, 3, 2), (6, 64, 4, 2), (6, 96, 3, 1),
          (6, 160, 3, 2), (6, 320, 1, 1))
FEATURE_BLOCK = 13  # the block whose expansion output is the first feature map (layer_15)
# TF OD API ssd_mobilenet_v2 extra layers: (1x1 bottleneck channels, 3x3 stride-2 output channels).
EXTRA_LAYERS = ((256, 512), (128, 256), (128, 256), (64, 128))


def same_padding(size: int, kernel: int, stride: int):
    """TensorFlow SAME: output ceil(size / stride), the padding split with the odd pixel after."""
    out = -(-size // stride)
    total = max((out - 1) * stride + kernel - size, 0)
    return total // 2, total - total // 2, out


class ConvSame(nn.Module):
    """Convolution (+ bias, batch norm folded in) with TF SAME padding for a fixed square input
    size, optionally followed by ReLU6. Symmetric padding goes into the convolution; the
    asymmetric case (stride 2 on an even size) uses an explicit zero pad first, which ONNX
    exports as a static Pad that OpenCV's DNN reads."""

    def __init__(self, cin: int, cout: int, kernel: int, stride: int, in_size: int,
                 depthwise: bool = False, relu6: bool = True):
        super().__init__()
        before, after, self.out_size = same_padding(in_size, kernel, stride)
        self.pad = nn.ZeroPad2d((before, after, before, after)) if before != after else None
        self.conv = nn.Conv2d(cin, cout, kernel, stride, padding=before if before == after else 0,
                              groups=cin if depthwise else 1, bias=True)
        self.act = nn.ReLU6() if relu6 else None
        self.depthwise = depthwise

    def forward(self, x):
        if self.pad is not None:
            x = self.pad(x)
        x = self.conv(x)
        return self.act(x) if self.act is not None else x


class InvertedResidual(nn.Module):
    def __init__(self, cin: int, cout: int, expansion: int, stride: int, in_size: int):
        super().__init__()
        hidden = cin * expansion
        self.expand = ConvSame(cin, hidden, 1, 1, in_size) if expansion != 1 else None
        self.depthwise = ConvSame(hidden, hidden, 3, stride, in_size, depthwise=True)
        self.project = ConvSame(hidden, cout, 1, 1, self.depthwise.out_size, relu6=False)
        self.residual = stride == 1 and cin == cout
        self.out_size = self.depthwise.out_size

    def convs(self):
        return [c for c in (self.expand, self.depthwise, self.project) if c is not None]

    def forward(self, x, return_expansion: bool = False):
        h = self.expand(x) if self.expand is not None else x
        e = h
        h = self.project(self.depthwise(h))
        if self.residual:
            h = h + x
        return (h, e) if return_expansion else h


class MobileNetV2Features(nn.Module):
    """MobileNetV2 1.0 up to Conv_1 (1280 channels); returns (layer_15 expansion, layer_19)."""

    def __init__(self, image_size: int = 300):
        super().__init__()
        self.conv0 = ConvSame(3, 32, 3, 2, image_size)
        size, cin, blocks = self.conv0.out_size, 32, []
        for t, c, n, s in BLOCKS:
            for i in range(n):
                blocks.append(InvertedResidual(cin, c, t, s if i == 0 else 1, size))
                size, cin = blocks[-1].out_size, c
        self.blocks = nn.ModuleList(blocks)
        self.conv1 = ConvSame(cin, 1280, 1, 1, size)
        self.out_size = size
        self.feature_sizes = (blocks[FEATURE_BLOCK - 1].out_size, size)
        self.feature_channels = (blocks[FEATURE_BLOCK].expand.conv.out_channels, 1280)

    def convs(self):
        """Every convolution in graph order (the order TFLite lists them)."""
        out = [self.conv0]
        for b in self.blocks:
            out += b.convs()
        return out + [self.conv1]

    def forward(self, x):
        return self.tail(self.stem(x, 0), 0)

    def stem(self, x, upto: int):
        """conv0 and blocks [0, upto): the part a partly frozen extractor computes once."""
        x = self.conv0(x)
        for block in self.blocks[:upto]:
            x = block(x)
        return x

    def tail(self, x, start: int):
        """Blocks [start, end) and conv1 on the stem's output: (layer_15 expansion, layer_19).
        start must not be past FEATURE_BLOCK, whose expansion output is the first map."""
        if start > FEATURE_BLOCK:
            raise ValueError("the tail must start at block %d or before" % FEATURE_BLOCK)
        f0 = None
        for i in range(start, len(self.blocks)):
            if i == FEATURE_BLOCK:
                x, f0 = self.blocks[i](x, return_expansion=True)
            else:
                x = self.blocks[i](x)
        return f0, self.conv1(x)

    def stem_shape(self, upto: int):
        """(size, channels) of stem(x, upto)'s output."""
        if upto == 0:
            return self.conv0.out_size, self.conv0.conv.out_channels
        b = self.blocks[upto - 1]
        return b.out_size, b.project.conv.out_channels


class SSDDetector(nn.Module):
    """Extra feature layers and box/class predictors on the two backbone feature maps."""

    def __init__(self, num_classes: int, feature_channels=(576, 1280), feature_sizes=(19, 10)):
        super().__init__()
        self.num_classes = num_classes
        extras, cin, size = [], feature_channels[1], feature_sizes[1]
        channels, sizes = list(feature_channels), list(feature_sizes)
        for bottleneck, cout in EXTRA_LAYERS:
            a = ConvSame(cin, bottleneck, 1, 1, size)
            b = ConvSame(bottleneck, cout, 3, 2, size)
            extras.append(nn.Sequential(a, b))
            cin, size = cout, b.out_size
            channels.append(cout)
            sizes.append(size)
        self.extras = nn.ModuleList(extras)
        self.feature_map_sizes = tuple(sizes)
        anchors = anchors_per_cell()
        self.box_heads = nn.ModuleList(ConvSame(c, a * 4, 1, 1, s, relu6=False)
                                       for c, a, s in zip(channels, anchors, sizes))
        self.class_heads = nn.ModuleList(ConvSame(c, a * (num_classes + 1), 1, 1, s, relu6=False)
                                         for c, a, s in zip(channels, anchors, sizes))

    def convs(self):
        """Extra-layer convolutions in graph order."""
        return [c for seq in self.extras for c in seq]

    def feature_maps(self, f0, f1):
        maps, x = [f0, f1], f1
        for layer in self.extras:
            x = layer(x)
            maps.append(x)
        return maps

    def forward(self, f0, f1):
        boxes, classes = [], []
        for x, bh, ch in zip(self.feature_maps(f0, f1), self.box_heads, self.class_heads):
            # NCHW -> NHWC then flatten: anchors ordered (row, column, anchor) as in TF.
            boxes.append(torch.flatten(bh(x).permute(0, 2, 3, 1), 1).reshape(x.shape[0], -1, 4))
            classes.append(torch.flatten(ch(x).permute(0, 2, 3, 1), 1)
                           .reshape(x.shape[0], -1, self.num_classes + 1))
        return torch.cat(boxes, 1), torch.cat(classes, 1)


class SSDMobileNetV2(nn.Module):
    def __init__(self, num_classes: int = 23, image_size: int = 300):
        super().__init__()
        self.image_size = image_size
        self.backbone = MobileNetV2Features(image_size)
        self.detector = SSDDetector(num_classes, self.backbone.feature_channels,
                                    self.backbone.feature_sizes)

    def forward(self, x):
        return self.detector(*self.backbone(x))


def init_class_heads(detector: SSDDetector, background_prior: float = 0.99) -> None:
    """Fresh class predictors: small random weights and a bias that starts every anchor at
    softmax probability `background_prior` for background, so the first steps are not dominated
    by the loss of ~1900 anchors all guessing foreground."""
    c = detector.num_classes
    bg_bias = math.log(background_prior * c / (1.0 - background_prior))
    for head in detector.class_heads:
        nn.init.normal_(head.conv.weight, std=0.01)
        bias = torch.zeros(head.conv.out_channels).view(-1, c + 1)
        bias[:, 0] = bg_bias
        head.conv.bias.data.copy_(bias.view(-1))


# ----------------------------------------------------------------------------------------------
# Weights from TFLite

def _copy_conv(dst: ConvSame, tfl: TfliteModel, op, where: str) -> None:
    """TFLite CONV_2D weights are OHWI, DEPTHWISE_CONV_2D weights 1HWC; PyTorch wants OIHW."""
    depthwise = op.op == "DEPTHWISE_CONV_2D"
    w = tfl.array(tfl.tensors[op.inputs[1]])
    b = tfl.array(tfl.tensors[op.inputs[2]]) if len(op.inputs) > 2 and op.inputs[2] >= 0 else None
    w = w[0].transpose(2, 0, 1)[:, None] if depthwise else w.transpose(0, 3, 1, 2)
    conv = dst.conv
    stride = (conv.stride[0], conv.stride[1])
    expect_act = "RELU6" if dst.act is not None else "NONE"
    if (depthwise != dst.depthwise or tuple(w.shape) != tuple(conv.weight.shape)
            or op.stride != stride or op.padding != "SAME" or op.activation != expect_act):
        raise ValueError("%s: TFLite %s weights %s stride %s %s %s do not fit PyTorch %s"
                         " stride %s %s" % (where, op.op, w.shape, op.stride, op.padding,
                                            op.activation, tuple(conv.weight.shape), stride,
                                            expect_act))
    with torch.no_grad():
        conv.weight.copy_(torch.from_numpy(np.ascontiguousarray(w)))
        conv.bias.copy_(torch.from_numpy(b) if b is not None else torch.zeros_like(conv.bias))


def _conv_ops(tfl: TfliteModel):
    return [op for op in tfl.operators if op.op in ("CONV_2D", "DEPTHWISE_CONV_2D")]


def _split_detector_ops(tfl: TfliteModel):
    """Conv ops of a TF OD API SSD graph: (feature extractor in order, box heads, class heads).
    A predictor is a convolution whose output feeds a RESHAPE; the RESHAPE's last dimension
    (4 for boxes) tells which predictor it is."""
    consumers = {}
    for op in tfl.operators:
        for i in op.inputs:
            consumers.setdefault(i, []).append(op)
    features, box, cls = [], [], []
    for op in _conv_ops(tfl):
        nxt = [c for c in consumers.get(op.outputs[0], []) if c.op == "RESHAPE"]
        if not nxt:
            features.append(op)
        elif tfl.tensors[nxt[0].outputs[0]].shape[-1] == 4:
            box.append(op)
        else:
            cls.append(op)
    return features, box, cls


def load_backbone_from_tflite(model: SSDMobileNetV2, path=MOBILENET_V2_IMAGENET) -> int:
    """The MobileNetV2 feature extractor from a TFLite MobileNetV2 1.0 (an ImageNet classifier,
    whose extra classifier convolution is left out, or a TF OD API SSD graph). Returns the number
    of convolutions loaded."""
    tfl = TfliteModel.read(path)
    ops = _split_detector_ops(tfl)[0]  # an ImageNet classifier's last 1x1 feeds a RESHAPE: out
    dst = model.backbone.convs()
    if len(ops) < len(dst):
        raise ValueError("%s has %d convolutions, fewer than MobileNetV2's %d"
                         % (path, len(ops), len(dst)))
    for i, (d, op) in enumerate(zip(dst, ops)):
        _copy_conv(d, tfl, op, "%s backbone conv %d" % (Path(path).name, i))
    return len(dst)


def load_detector_from_tflite(model: SSDMobileNetV2, path=SSD_OIDV4, class_heads: bool = True,
                              backbone: bool = False) -> int:
    """Extra layers and box predictors (and, if asked, class predictors and the feature
    extractor) from a TF OD API SSD-MobileNetV2 TFLite graph. Class predictors are copied only
    when their shapes match. Returns the number of convolutions loaded."""
    tfl = TfliteModel.read(path)
    features, box, cls = _split_detector_ops(tfl)
    nb = len(model.backbone.convs())
    extras = model.detector.convs()
    if len(features) != nb + len(extras) or len(box) != 6 or len(cls) != 6:
        raise ValueError("%s is not an SSD-MobileNetV2 graph: %d feature convolutions (expected"
                         " %d), %d box and %d class predictors (expected 6 and 6)"
                         % (path, len(features), nb + len(extras), len(box), len(cls)))
    name = Path(path).name
    count = 0
    if backbone:
        for i, (d, op) in enumerate(zip(model.backbone.convs(), features[:nb])):
            _copy_conv(d, tfl, op, "%s backbone conv %d" % (name, i))
            count += 1
    for i, (d, op) in enumerate(zip(extras, features[nb:])):
        _copy_conv(d, tfl, op, "%s extra conv %d" % (name, i))
        count += 1
    for i, (d, op) in enumerate(zip(model.detector.box_heads, box)):
        _copy_conv(d, tfl, op, "%s box predictor %d" % (name, i))
        count += 1
    if class_heads:
        for i, (d, op) in enumerate(zip(model.detector.class_heads, cls)):
            if tfl.tensors[op.inputs[1]].shape[0] != d.conv.out_channels:
                raise ValueError("%s class predictor %d has %d outputs, the model %d"
                                 % (name, i, tfl.tensors[op.inputs[1]].shape[0],
                                    d.conv.out_channels))
            _copy_conv(d, tfl, op, "%s class predictor %d" % (name, i))
            count += 1
    return count


def build_model(num_classes: int = 23, backbone: str = "imagenet",
                class_heads: str = "random", models_dir=None) -> SSDMobileNetV2:
    """The transfer-learning starting point.
    backbone: 'imagenet' (MobileNetV2 ImageNet, the paper's frozen extractor) or 'oidv4'
    (the OIDv4 detector's fine-tuned extractor). class_heads: 'random' (init_class_heads) or
    'oidv4' (the Open Images predictors, only if num_classes == 23)."""
    mdir = Path(models_dir) if models_dir else MODELS_DIR
    imagenet = mdir / MOBILENET_V2_IMAGENET.relative_to(MODELS_DIR)
    oidv4 = mdir / SSD_OIDV4.relative_to(MODELS_DIR)
    model = SSDMobileNetV2(num_classes)
    if backbone == "imagenet":
        load_backbone_from_tflite(model, imagenet)
    elif backbone != "oidv4":
        raise ValueError("backbone must be 'imagenet' or 'oidv4', not %r" % backbone)
    load_detector_from_tflite(model, oidv4, class_heads=(class_heads == "oidv4"),
                              backbone=(backbone == "oidv4"))
    if class_heads == "random":
        init_class_heads(model.detector)
    elif class_heads != "oidv4":
        raise ValueError("class_heads must be 'random' or 'oidv4', not %r" % class_heads)
    return model


def load_onnx_weights(model: SSDMobileNetV2, path) -> None:
    """Every parameter from an ONNX file export_onnx wrote (its initialisers keep the PyTorch
    names); the model must have the same layers and classes."""
    import onnx
    from onnx import numpy_helper
    weights = {i.name: numpy_helper.to_array(i) for i in onnx.load(str(path)).graph.initializer}
    state = model.state_dict()
    missing = [k for k in state if k not in weights]
    if missing:
        raise ValueError("%s: no weights for %s (not a model of this layout)" % (path, missing[0]))
    for k, v in state.items():
        if tuple(weights[k].shape) != tuple(v.shape):
            raise ValueError("%s: %s has shape %s, the model %s" % (path, k, weights[k].shape, tuple(v.shape)))
        state[k] = torch.from_numpy(weights[k].copy())
    model.load_state_dict(state)


def preprocess(rgb: np.ndarray, size: int = 300) -> torch.Tensor:
    """HxWx3 uint8 RGB -> [1, 3, size, size] float in [-1, 1] (bilinear resize, no crop), the
    input convention of the TF OD API MobileNet models: x / 127.5 - 1."""
    from PIL import Image
    img = Image.fromarray(rgb).resize((size, size), Image.BILINEAR)
    x = np.asarray(img, np.float32) / 127.5 - 1.0
    return torch.from_numpy(x.transpose(2, 0, 1).copy())[None]
