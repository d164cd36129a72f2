"""Pictures in tests (the simulator's, the lab page's): which pixels are RRBot's orange or the
coke can's red (lit or in shade, as MuJoCo draws them), and PNG files in and out (through Qt's
QImage, which needs no display), so a test can keep what it saw for a human in its artifact
folder."""
import numpy as np
from PyQt5.QtGui import QImage


def _channels(image: np.ndarray):
    return (image[..., i].astype(int) for i in range(3))


def orange_pixels(image: np.ndarray) -> np.ndarray:
    """RRBot's links 1 and 3 (URDF rgba 1 0.42 0.04): e.g. 126 72 36 in shade."""
    r, g, b = _channels(image)
    return (r >= 80) & (g * 100 >= 35 * r) & (g * 100 <= 75 * r) & (b * 100 <= 45 * r)


def red_pixels(image: np.ndarray) -> np.ndarray:
    """The coke can (and RRBot's small camera box): red, lit or in shade."""
    r, g, b = _channels(image)
    return (r > 90) & (r > 3 * g) & (r > 3 * b)


def changed_pixels(a: np.ndarray, b: np.ndarray) -> int:
    return int((np.abs(a.astype(int) - b.astype(int)).sum(axis=2) > 30).sum())


def save_png(image: np.ndarray, path: str) -> str:
    """Write an (height, width, 3) uint8 RGB array as a PNG; returns the path."""
    image = np.ascontiguousarray(image, dtype=np.uint8)
    height, width = image.shape[:2]
    qimage = QImage(image.data, width, height, width * 3, QImage.Format_RGB888)
    if not qimage.save(path, "PNG"):
        raise OSError("could not write %s" % path)
    return path


def load_png(path: str) -> np.ndarray:
    """A PNG (e.g. a screenshot) as an (height, width, 3) uint8 RGB array."""
    qimage = QImage(path)
    if qimage.isNull():
        raise OSError("could not read %s" % path)
    qimage = qimage.convertToFormat(QImage.Format_RGB888)
    height, width, stride = qimage.height(), qimage.width(), qimage.bytesPerLine()
    buffer = np.frombuffer(qimage.constBits().asstring(stride * height), dtype=np.uint8)
    return buffer.reshape(height, stride)[:, :width * 3].reshape(height, width, 3).copy()
