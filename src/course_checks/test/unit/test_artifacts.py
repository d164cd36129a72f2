"""What save_canvas may copy into a student's outputs: a PNG at a plain path, never through a link,
never a device or a FIFO, never a huge file (course_checks.artifacts.read_png)."""
from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from course_checks.artifacts import PNG_SIGNATURE, UnsafeFile, read_png

PICTURE = PNG_SIGNATURE + b"\x00\x00\x00\rIHDR" + bytes(range(64))


@pytest.fixture
def png(tmp_path: Path) -> Path:
    path = tmp_path / "canvas.png"
    path.write_bytes(PICTURE)
    return path


def test_a_png_is_read_whole(png: Path):
    assert read_png(str(png)) == PICTURE


def test_a_symlink_to_a_png_is_refused(png: Path, tmp_path: Path):
    link = tmp_path / "link.png"
    link.symlink_to(png)
    with pytest.raises(OSError):  # ELOOP from O_NOFOLLOW
        read_png(str(link))


def test_a_symlinked_folder_on_the_way_is_refused(png: Path, tmp_path: Path):
    (tmp_path / "via").symlink_to(tmp_path)
    with pytest.raises(OSError):
        read_png(str(tmp_path / "via" / "canvas.png"))


def test_a_file_that_is_not_a_png_is_refused(tmp_path: Path):
    secret = tmp_path / "shadow"
    secret.write_text("root:$6$secret:19000:0:99999:7:::\n")
    with pytest.raises(UnsafeFile, match="not a PNG"):
        read_png(str(secret))
    with pytest.raises(UnsafeFile, match="not a PNG"):
        read_png("/etc/passwd")


def test_a_fifo_or_device_is_refused_without_blocking(tmp_path: Path):
    fifo = tmp_path / "pipe.png"
    os.mkfifo(fifo)
    with pytest.raises(UnsafeFile, match="not a regular file"):
        read_png(str(fifo))
    with pytest.raises(UnsafeFile, match="not a regular file"):
        read_png("/dev/zero")


def test_a_folder_is_refused(tmp_path: Path):
    with pytest.raises(UnsafeFile, match="not a regular file"):
        read_png(str(tmp_path))


def test_a_png_over_the_limit_is_refused(tmp_path: Path):
    big = tmp_path / "big.png"
    big.write_bytes(PICTURE + bytes(1000))
    assert read_png(str(big), limit=len(PICTURE) + 1000) == PICTURE + bytes(1000)
    with pytest.raises(UnsafeFile, match="more than"):
        read_png(str(big), limit=len(PICTURE) + 999)


@pytest.mark.parametrize("path", ["canvas.png", "", "/", "/tmp/../etc/passwd", "/tmp/./x.png"])
def test_relative_and_roundabout_paths_are_refused(path: str):
    with pytest.raises(UnsafeFile):
        read_png(path)


@settings(max_examples=100, deadline=None)
@given(st.binary(max_size=64))
def test_only_files_starting_with_the_png_signature_are_read(tmp_path_factory, content: bytes):
    path = tmp_path_factory.mktemp("any") / "file"
    path.write_bytes(content)
    if content.startswith(PNG_SIGNATURE):
        assert read_png(str(path)) == content
    else:
        with pytest.raises(UnsafeFile):
            read_png(str(path))
