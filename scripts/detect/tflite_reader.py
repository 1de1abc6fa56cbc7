"""Read the weights and the graph of a TFLite flatbuffer without TensorFlow.

Only the few tables of tensorflow/lite/schema/schema.fbs that weight conversion needs are read:
Model.operator_codes/subgraphs/buffers, SubGraph.tensors/inputs/outputs/operators,
Tensor.shape/type/buffer/name/quantization, QuantizationParameters.scale/zero_point/
quantized_dimension, Operator.opcode_index/inputs/outputs/builtin_options (for the convolutions'
padding, strides and fused activation), OperatorCode.builtin_code. Tables are walked with the
`flatbuffers` runtime (Debian: python3-flatbuffers); the field slots are 4 + 2 * field id of the
schema, so no generated code is needed.

    model = TfliteModel.read(path)
    w = model.array("MobilenetV2/Conv/Conv2D_Fold")   # float32, dequantised
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
from flatbuffers import encode, packer
from flatbuffers import number_types as N
from flatbuffers.table import Table

# schema.fbs enum TensorType: value -> numpy dtype of the stored bytes.
TENSOR_TYPES = {0: np.float32, 1: np.float16, 2: np.int32, 3: np.uint8, 4: np.int64,
                6: np.bool_, 7: np.int16, 9: np.int8, 10: np.float64}
TENSOR_TYPE_NAMES = {0: "FLOAT32", 1: "FLOAT16", 2: "INT32", 3: "UINT8", 4: "INT64",
                     5: "STRING", 6: "BOOL", 7: "INT16", 9: "INT8", 10: "FLOAT64"}
# schema.fbs enum BuiltinOperator, the operators these models use.
BUILTIN_OPS = {0: "ADD", 1: "AVERAGE_POOL_2D", 2: "CONCATENATION", 3: "CONV_2D",
               4: "DEPTHWISE_CONV_2D", 6: "DEQUANTIZE", 9: "FULLY_CONNECTED", 14: "LOGISTIC",
               21: "RELU6", 22: "RESHAPE", 25: "SOFTMAX", 40: "MEAN", 114: "QUANTIZE"}
# Conv2DOptions / DepthwiseConv2DOptions enums.
PADDINGS = {0: "SAME", 1: "VALID"}
ACTIVATIONS = {0: "NONE", 1: "RELU", 2: "RELU_N1_TO_1", 3: "RELU6", 4: "TANH"}


class _Table:
    """A flatbuffer table read by field id (slot 4 + 2 * id), as the schema numbers fields."""

    def __init__(self, buf: bytes, pos: int):
        self.t = Table(buf, pos)

    def _off(self, field: int) -> int:
        return self.t.Offset(4 + 2 * field)

    def scalar(self, field: int, flags, default):
        off = self._off(field)
        return self.t.Get(flags, self.t.Pos + off) if off else default

    def string(self, field: int) -> str:
        off = self._off(field)
        return self.t.String(self.t.Pos + off).decode("utf-8") if off else ""

    def table(self, field: int) -> "_Table | None":
        off = self._off(field)
        return _Table(self.t.Bytes, self.t.Indirect(self.t.Pos + off)) if off else None

    def tables(self, field: int) -> list["_Table"]:
        off = self._off(field)
        if not off:
            return []
        start = self.t.Vector(off)
        return [_Table(self.t.Bytes, self.t.Indirect(start + 4 * i))
                for i in range(self.t.VectorLen(off))]

    def vector(self, field: int, flags) -> np.ndarray:
        off = self._off(field)
        if not off:
            return np.zeros(0, dtype=flags.py_type)
        return self.t.GetVectorAsNumpy(flags, off)


@dataclasses.dataclass
class Tensor:
    index: int
    name: str
    shape: tuple
    type: int               # schema TensorType
    buffer: int             # index into Model.buffers; 0 is the empty buffer
    scale: np.ndarray       # quantisation scales (empty: not quantised)
    zero_point: np.ndarray
    quantized_dimension: int

    @property
    def type_name(self) -> str:
        return TENSOR_TYPE_NAMES.get(self.type, str(self.type))


@dataclasses.dataclass
class Operator:
    op: str                 # builtin operator name ("CONV_2D"), or "OP<code>" if not listed
    inputs: list            # tensor indices, -1 for an omitted optional input
    outputs: list
    padding: str = ""       # convolutions only: "SAME" or "VALID"
    stride: tuple = (1, 1)  # (h, w)
    activation: str = "NONE"
    depth_multiplier: int = 1


class TfliteModel:
    """The first subgraph of a TFLite model: its tensors, constant data and operators."""

    def __init__(self, buf: bytes):
        if buf[4:8] != b"TFL3":
            raise ValueError("not a TFLite flatbuffer (file identifier %r, expected b'TFL3')"
                             % bytes(buf[4:8]))
        self._buf = buf
        model = _Table(buf, encode.Get(packer.uoffset, buf, 0))
        self.version = model.scalar(0, N.Uint32Flags, 0)
        codes = []
        for oc in model.tables(1):
            # builtin_code (field 3, int32) supersedes deprecated_builtin_code (field 0, int8).
            code = max(oc.scalar(3, N.Int32Flags, 0), oc.scalar(0, N.Int8Flags, 0))
            codes.append(BUILTIN_OPS.get(code, "OP%d" % code))
        subgraphs = model.tables(2)
        if not subgraphs:
            raise ValueError("TFLite model has no subgraph")
        self._buffers = model.tables(4)
        sg = subgraphs[0]
        self.tensors = [self._tensor(i, t) for i, t in enumerate(sg.tables(0))]
        self.inputs = list(sg.vector(1, N.Int32Flags))
        self.outputs = list(sg.vector(2, N.Int32Flags))
        self.operators = [self._operator(o, codes) for o in sg.tables(3)]
        self._by_name = {t.name: t for t in self.tensors}
        # The output of a DEQUANTIZE of a constant is itself a constant: its data is the input's.
        self._dequantized_from = {o.outputs[0]: o.inputs[0] for o in self.operators
                                  if o.op == "DEQUANTIZE" and self.tensors[o.inputs[0]].buffer}

    @classmethod
    def read(cls, path) -> "TfliteModel":
        return cls(Path(path).read_bytes())

    @staticmethod
    def _tensor(index: int, t: _Table) -> Tensor:
        q = t.table(4)
        scale = q.vector(2, N.Float32Flags).copy() if q else np.zeros(0, np.float32)
        zero_point = q.vector(3, N.Int64Flags).copy() if q else np.zeros(0, np.int64)
        qdim = q.scalar(6, N.Int32Flags, 0) if q else 0
        return Tensor(index=index, name=t.string(3), shape=tuple(int(s) for s in t.vector(0, N.Int32Flags)),
                      type=t.scalar(1, N.Int8Flags, 0), buffer=t.scalar(2, N.Uint32Flags, 0),
                      scale=scale, zero_point=zero_point, quantized_dimension=qdim)

    @staticmethod
    def _operator(o: _Table, codes: list) -> Operator:
        op = Operator(op=codes[o.scalar(0, N.Uint32Flags, 0)],
                      inputs=[int(i) for i in o.vector(1, N.Int32Flags)],
                      outputs=[int(i) for i in o.vector(2, N.Int32Flags)])
        if op.op in ("CONV_2D", "DEPTHWISE_CONV_2D"):
            opts = o.table(4)  # builtin_options: Conv2DOptions / DepthwiseConv2DOptions
            if opts is not None:
                depthwise = op.op == "DEPTHWISE_CONV_2D"
                op.padding = PADDINGS[opts.scalar(0, N.Int8Flags, 0)]
                op.stride = (opts.scalar(2, N.Int32Flags, 0), opts.scalar(1, N.Int32Flags, 0))
                op.activation = ACTIVATIONS.get(opts.scalar(4 if depthwise else 3, N.Int8Flags, 0), "?")
                if depthwise:
                    op.depth_multiplier = opts.scalar(3, N.Int32Flags, 1)
        return op

    def tensor(self, name: str) -> Tensor:
        try:
            return self._by_name[name]
        except KeyError:
            raise KeyError("no tensor named %r in the TFLite model" % name) from None

    def raw(self, t: Tensor) -> np.ndarray:
        """The stored values of a constant tensor, in its stored type (not dequantised)."""
        if t.index in self._dequantized_from:
            t = self.tensors[self._dequantized_from[t.index]]
        if t.type not in TENSOR_TYPES:
            raise ValueError("tensor %r has type %s, which this reader does not convert"
                             % (t.name, t.type_name))
        data = self._buffers[t.buffer].vector(0, N.Uint8Flags) if t.buffer else None
        if data is None or data.size == 0:
            raise ValueError("tensor %r is not a constant (it has no data buffer)" % t.name)
        return np.frombuffer(data.tobytes(), dtype=TENSOR_TYPES[t.type]).reshape(t.shape)

    def array(self, name_or_tensor) -> np.ndarray:
        """A constant tensor as float32 (int32 for unquantised integers), dequantised:
        int8 per channel along quantized_dimension, uint8 per tensor, fp16 widened."""
        t = name_or_tensor if isinstance(name_or_tensor, Tensor) else self.tensor(name_or_tensor)
        src = self.tensors[self._dequantized_from.get(t.index, t.index)]
        q = self.raw(src)
        if src.type == 1:
            return q.astype(np.float32)
        if src.scale.size == 0 or src.type in (0, 10):
            return q.astype(np.float32) if q.dtype.kind == "f" else q.copy()
        bshape = [1] * q.ndim
        if src.scale.size > 1:
            bshape[src.quantized_dimension] = src.scale.size
        scale = src.scale.reshape(bshape).astype(np.float64)
        zp = src.zero_point.reshape(bshape) if src.zero_point.size == src.scale.size else 0
        return ((q.astype(np.int64) - zp) * scale).astype(np.float32)

    def constants(self) -> dict:
        """Every tensor that holds data, by name, dequantised."""
        out = {}
        for t in self.tensors:
            if t.buffer or t.index in self._dequantized_from:
                try:
                    out[t.name] = self.array(t)
                except ValueError:
                    pass
        return out

    def producer(self, tensor_index: int):
        """The operator that writes the tensor, or None for inputs and constants."""
        for op in self.operators:
            if tensor_index in op.outputs:
                return op
        return None


def main(argv=None) -> int:
    import argparse
    ap = argparse.ArgumentParser(description="List the tensors and operators of a TFLite model.")
    ap.add_argument("model")
    ap.add_argument("--ops", action="store_true", help="list the operators in graph order")
    args = ap.parse_args(argv)
    m = TfliteModel.read(args.model)
    if args.ops:
        for i, op in enumerate(m.operators):
            print(i, op.op, op.padding, op.stride, op.activation,
                  [m.tensors[k].name if k >= 0 else "-" for k in op.inputs], "->",
                  [m.tensors[k].name for k in op.outputs])
    else:
        for t in m.tensors:
            q = " scale[%d]" % t.scale.size if t.scale.size else ""
            print(t.index, t.name, t.shape, t.type_name, "buffer=%d" % t.buffer, q)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
