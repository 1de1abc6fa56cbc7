#!/usr/bin/python3
"""Independent check of `flexsight cloud`: meshio (a PLY reader we did not write) reads
the binary and ASCII clouds of the fixture's ground-truth disparity, and the points must
equal the Middlebury formula Z = baseline * f / (d + doffs) computed here with NumPy.

usage: ply_meshio_check.py FLEXSIGHT_BINARY FIXTURE_DIR
"""
import os
import subprocess
import sys
import tempfile

import meshio
import numpy as np
from PIL import Image

# The project's PFM reader (scripts/stereo/pfm_io.py).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "stereo"))
from pfm_io import read_pfm  # noqa: E402


def read_calib(path):
    values = {}
    for line in open(path):
        key, _, value = line.strip().partition("=")
        values[key] = value
    cam0 = [float(v) for v in values["cam0"].strip("[]").replace(";", " ").split()]
    return cam0[0], cam0[2], cam0[5], float(values["doffs"]), float(values["baseline"])


def main():
    binary, fixture = sys.argv[1], sys.argv[2]
    disparity = read_pfm(os.path.join(fixture, "disp0GT.pfm"))
    image = np.asarray(Image.open(os.path.join(fixture, "im0.png")).convert("RGB"))
    f, cx, cy, doffs, baseline = read_calib(os.path.join(fixture, "calib.txt"))
    ys, xs = np.nonzero(np.isfinite(disparity) & (disparity >= 0))  # row-major order
    d = disparity[ys, xs].astype(np.float64)
    z = baseline * f / (d + doffs)
    expected = np.stack([(xs - cx) * z / f, (ys - cy) * z / f, z], axis=1)

    with tempfile.TemporaryDirectory() as tmp:
        for ascii_flag in ([], ["--ply-ascii"]):
            out = os.path.join(tmp, "cloud.ply")
            subprocess.run([binary, "cloud", os.path.join(fixture, "disp0GT.pfm"),
                            os.path.join(fixture, "im0.png"), "--calib",
                            os.path.join(fixture, "calib.txt"), "-o", out] + ascii_flag,
                           check=True, stdout=subprocess.DEVNULL)
            mesh = meshio.read(out)
            name = "ascii" if ascii_flag else "binary"
            assert mesh.points.shape == expected.shape, (name, mesh.points.shape, expected.shape)
            np.testing.assert_allclose(mesh.points, expected, rtol=2e-6, atol=1e-4, err_msg=name)
            # meshio 7.0 returns PLY uchar as int8; the bytes are what matter.
            colors = np.stack([mesh.point_data[c].astype(np.int8).view(np.uint8)
                               for c in ("red", "green", "blue")], axis=1)
            np.testing.assert_array_equal(colors, image[ys, xs], err_msg=name)
            normals = np.stack([mesh.point_data[c] for c in ("nx", "ny", "nz")], axis=1)
            np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-5)
            facing = np.einsum("ij,ij->i", normals, mesh.points)
            assert (facing <= 0).all(), f"{name}: {int((facing > 0).sum())} normals face away"
            print(f"{name}: {len(mesh.points)} points equal the Middlebury formula")


if __name__ == "__main__":
    main()
