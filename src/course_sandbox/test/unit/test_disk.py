"""disk: what a folder tree takes (allocated blocks, links not followed) and the bound's meter."""
import os

from course_sandbox import disk

MiB = 1 << 20


def write(path, size):
    with open(path, "wb") as f:
        f.write(os.urandom(size))


def test_used_bytes_counts_blocks_of_the_whole_tree_and_no_link(tmp_path):
    (tmp_path / "a" / "b").mkdir(parents=True)
    write(tmp_path / "a" / "b" / "f", 3 * MiB)
    write(tmp_path / "g", 1 * MiB)
    outside = tmp_path.parent / (tmp_path.name + "-outside")
    outside.mkdir()
    write(outside / "big", 4 * MiB)
    os.symlink(outside, tmp_path / "link")
    with open(tmp_path / "sparse", "wb") as f:
        f.truncate(1 << 30)  # a sparse GiB fills nothing
    used = disk.used_bytes(str(tmp_path))
    assert 4 * MiB <= used < 4 * MiB + MiB // 2


def test_the_meter_measures_once_per_interval_and_says_past_the_bound(tmp_path):
    meter = disk.DiskMeter(str(tmp_path), 2 * MiB, interval=10.0)
    assert not meter.over(now=100.0)
    write(tmp_path / "f", 3 * MiB)
    assert not meter.over(now=105.0)  # within the interval: the last answer
    assert meter.over(now=110.0)
    assert meter.over(now=float("inf"))


def test_the_sentence_names_the_bound():
    assert "more than 512 MiB to disk together" in disk.sentence(512 * MiB)
