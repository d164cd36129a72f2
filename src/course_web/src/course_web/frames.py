"""sensor_msgs/Image -> a compressed picture in one binary websocket frame.

A browser draws JPEG or PNG natively (createImageBitmap), so the server compresses each frame
once, whoever watches, and sends it as a binary frame: 4 bytes (big-endian length of a JSON
header), the header ({"op": "image", "topic", "format", "width", "height", "stamp"}), then the
picture. A 500x500 turtlesim canvas is ~750 kB raw and ~1 MB as rosbridge's base64 JSON; as
JPEG it is ~15-25 kB, which is what makes 20+ fps to many viewers affordable. Pillow (Debian's
python3-pil) compresses, because it needs no Qt application and releases the GIL while it works.

Pillow is imported on the first picture, not with this module: lab_view imports this module at
start, and Pillow (with its C library and the image libraries it links) costs about 1.5 MiB of
resident memory in every student's container, while the page itself asks for no picture (it draws
the turtlesim canvas from ~scene); only a camera panel or a rosbridge client asking "compression"
does.
"""
from __future__ import annotations

import io
import json
import struct
from typing import TYPE_CHECKING, Any, Dict, Tuple

if TYPE_CHECKING:
    from PIL import Image

# ROS encodings Pillow can take as they are: (Pillow mode, bytes per pixel, channel swap).
ENCODINGS = {
    "rgb8": ("RGB", 3, None), "bgr8": ("RGB", 3, "BGR"), "rgba8": ("RGBA", 4, None),
    "bgra8": ("RGBA", 4, "BGRA"), "mono8": ("L", 1, None), "8UC1": ("L", 1, None), "8UC3": ("RGB", 3, "BGR"),
}
JPEG_QUALITY = 85
HEADER_LENGTH = struct.Struct(">I")


class FrameError(ValueError):
    """The image cannot be turned into a picture (an encoding we do not draw, a short buffer)."""


def to_picture(encoding: str, width: int, height: int, step: int, data: bytes) -> Image.Image:
    """The raw image as a Pillow picture."""
    from PIL import Image  # imported here: see the module docstring
    if encoding not in ENCODINGS:
        raise FrameError("image encoding %r is not drawn (known: %s)" % (encoding, ", ".join(sorted(ENCODINGS))))
    mode, depth, raw_mode = ENCODINGS[encoding]
    if width <= 0 or height <= 0 or step < width * depth or len(data) < step * height:
        raise FrameError("image %dx%d %s with step %d does not fit its %d bytes" % (width, height, encoding, step, len(data)))
    return Image.frombuffer(mode, (width, height), bytes(data), "raw", raw_mode or mode, step, 1)


def compress(picture: Image.Image, fmt: str) -> bytes:
    """The picture as JPEG ("jpeg") or PNG ("png") bytes."""
    out = io.BytesIO()
    if fmt == "jpeg":
        picture.convert("RGB" if picture.mode != "L" else "L").save(out, "JPEG", quality=JPEG_QUALITY)
    elif fmt == "png":
        picture.save(out, "PNG", compress_level=1)
    else:
        raise FrameError("picture format %r is not jpeg or png" % fmt)
    return out.getvalue()


def pack(header: Dict[str, Any], body: bytes) -> bytes:
    """One binary frame: header length, JSON header, body."""
    head = json.dumps(header, separators=(",", ":")).encode("utf-8")
    return HEADER_LENGTH.pack(len(head)) + head + body


def unpack(frame: bytes) -> Tuple[Dict[str, Any], bytes]:
    """The header and body of a frame made by pack()."""
    (length,) = HEADER_LENGTH.unpack_from(frame)
    end = HEADER_LENGTH.size + length
    return json.loads(frame[HEADER_LENGTH.size:end].decode("utf-8")), frame[end:]


def image_frame(topic: str, fmt: str, encoding: str, width: int, height: int, step: int,
                data: bytes, stamp: Dict[str, int]) -> bytes:
    """A sensor_msgs/Image's fields as one binary frame carrying a `fmt` picture."""
    body = compress(to_picture(encoding, width, height, step, data), fmt)
    return pack({"op": "image", "topic": topic, "format": fmt, "width": width, "height": height,
                 "stamp": stamp}, body)
