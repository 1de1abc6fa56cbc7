"""PFM (Middlebury's float images) for the Python tools: one reader, one writer."""
import numpy as np


def read_pfm(path, expect_channels=None):
    """Rows top-down as float32, shape (h, w) for 'Pf' or (h, w, 3) for 'PF'; either byte
    order. Exits with a message naming the file when expect_channels does not match."""
    with open(path, "rb") as f:
        magic = f.readline().strip()
        if magic not in (b"Pf", b"PF"):
            raise SystemExit(f"{path}: not a PFM (magic {magic!r})")
        channels = 3 if magic == b"PF" else 1
        if expect_channels is not None and channels != expect_channels:
            raise SystemExit(f"{path}: expected a {expect_channels}-channel PFM, got {magic!r}")
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(width * height * channels * 4),
                             dtype="<f4" if scale < 0 else ">f4")
    image = np.flipud(data.reshape(height, width, channels)).astype(np.float32)
    return image[:, :, 0] if channels == 1 else image


def write_pfm(path, image):
    """A one-channel little-endian PFM, bottom row first."""
    height, width = image.shape
    with open(path, "wb") as f:
        f.write(b"Pf\n%d %d\n-1\n" % (width, height))
        f.write(np.flipud(image).astype("<f4").tobytes())
