"""course_testkit.multiarch without podman or qemu: the architecture names, each image's and base's
name, which binfmt_misc entries a container can use, and the platforms read off a manifest list.
(`make image-multiarch` and `make image-arm64-check` run the real thing, as root, in hours.)"""
import pytest

from course_testkit import multiarch


def test_machines_map_to_the_two_image_architectures_and_others_are_refused():
    assert [multiarch.oci_arch(m) for m in ("x86_64", "aarch64", "arm64", "AMD64")] == \
        ["amd64", "arm64", "arm64", "amd64"]
    with pytest.raises(ValueError, match="riscv64"):
        multiarch.oci_arch("riscv64")


def test_each_architecture_has_its_own_tag_and_the_host_keeps_the_shared_base():
    assert multiarch.image_name("arm64") == "localhost/ros-course-arm64"
    assert multiarch.image_name("amd64") == "localhost/ros-course-amd64"
    with pytest.raises(ValueError):
        multiarch.image_name("armhf")
    # the host's base is the one course_testkit.podman imports; a foreign one never takes its name
    assert multiarch.base_image("amd64", "amd64") == "debian:bookworm"
    assert multiarch.base_image("arm64", "amd64") == "localhost/debian:bookworm-arm64"
    assert multiarch.base_image("amd64", "arm64") == "localhost/debian:bookworm-amd64"
    assert multiarch.binfmt_entry("arm64") == "qemu-aarch64"


AARCH64 = ("interpreter /usr/libexec/qemu-binfmt/aarch64-binfmt-P\nflags: %s\noffset 0\n"
           "magic 7f454c460201010000000000000000000200b700\n")


def test_only_an_enabled_entry_with_the_f_flag_serves_containers():
    assert multiarch.binfmt_usable("enabled\n" + AARCH64 % "PF")
    assert multiarch.binfmt_usable("enabled\n" + AARCH64 % "OCF")
    # without F the kernel looks the emulator up inside the container, where there is none
    assert not multiarch.binfmt_usable("enabled\n" + AARCH64 % "P")
    assert not multiarch.binfmt_usable("disabled\n" + AARCH64 % "PF")
    assert not multiarch.binfmt_usable("")


def test_manifest_platforms_are_read_off_podman_manifest_inspect():
    inspect = {"schemaVersion": 2, "mediaType": "application/vnd.docker.distribution.manifest.list.v2+json",
               "manifests": [{"digest": "sha256:1", "platform": {"architecture": "arm64", "os": "linux"}},
                             {"digest": "sha256:2", "platform": {"architecture": "amd64", "os": "linux"}}]}
    assert multiarch.manifest_platforms(inspect) == ["linux/amd64", "linux/arm64"]
    assert multiarch.manifest_platforms({"manifests": None}) == []
