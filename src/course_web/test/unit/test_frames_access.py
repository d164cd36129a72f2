"""course_web.frames (images as binary frames) and course_web.access (the token rule)."""
from __future__ import annotations

import io

import pytest
from PIL import Image

from course_web import access, frames

BACKGROUND = (69, 86, 255)


def raw_canvas(width=40, height=30, colour=BACKGROUND, padding=0):
    row = bytes(colour) * width + b"\0" * padding
    return row * height


@pytest.mark.parametrize("fmt", ["png", "jpeg"])
def test_an_rgb8_image_travels_as_a_picture_with_its_header(fmt):
    frame = frames.image_frame("/turtlesim/image", fmt, "rgb8", 40, 30, 40 * 3 + 4,
                               raw_canvas(padding=4), {"secs": 1, "nsecs": 2})
    header, body = frames.unpack(frame)
    assert header == {"op": "image", "topic": "/turtlesim/image", "format": fmt, "width": 40, "height": 30,
                      "stamp": {"secs": 1, "nsecs": 2}}
    picture = Image.open(io.BytesIO(body)).convert("RGB")
    assert picture.size == (40, 30)
    assert all(abs(a - b) <= 3 for a, b in zip(picture.getpixel((20, 15)), BACKGROUND))


def test_bgr8_is_swapped_to_rgb():
    picture = frames.to_picture("bgr8", 2, 1, 6, bytes([1, 2, 3, 4, 5, 6]))
    assert picture.getpixel((0, 0)) == (3, 2, 1)


@pytest.mark.parametrize("encoding, width, step, data, complaint", [
    ("32FC1", 2, 8, b"\0" * 8, "not drawn"),
    ("rgb8", 2, 6, b"\0" * 5, "does not fit"),
    ("rgb8", 2, 5, b"\0" * 6, "does not fit"),
    ("rgb8", 0, 0, b"", "does not fit"),
])
def test_images_that_cannot_be_drawn_are_refused(encoding, width, step, data, complaint):
    with pytest.raises(frames.FrameError, match=complaint):
        frames.to_picture(encoding, width, 1, step, data)


def test_loopback_needs_no_token_and_other_addresses_get_one():
    assert access.token_for("127.0.0.1", "") is None
    assert access.token_for("localhost", "") is None
    assert access.token_for("::1", "") is None
    generated = access.token_for("0.0.0.0", "")
    assert generated and len(generated) >= 20 and generated != access.token_for("0.0.0.0", "")
    assert access.token_for("0.0.0.0", "given") == "given"


def test_allowed_compares_the_token():
    assert access.allowed(None, None)
    assert access.allowed("abc", "abc")
    assert not access.allowed("abc", None)
    assert not access.allowed("abc", "abd")


def test_the_printed_url_carries_the_token():
    assert access.page_url("127.0.0.1", 8080, None) == "http://127.0.0.1:8080/"
    assert access.page_url("10.0.0.5", 9000, "t0k") == "http://10.0.0.5:9000/?token=t0k"
    assert access.page_url("0.0.0.0", 8080, "t0k", "127.0.0.1") == "http://127.0.0.1:8080/?token=t0k"
