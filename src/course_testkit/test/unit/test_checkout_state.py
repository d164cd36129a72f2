"""sample_grading.git_state in a tree without .git (the course image's /course): it reads the files
themselves, so a grading that changes the course still shows, and a test that needs git's own
view learns why there is none (not_a_checkout)."""
import os
import subprocess

from course_testkit.sample_grading import git_state, not_a_checkout


def _tree(root):
    root.mkdir()
    (root / ".gitignore").write_text("/output/\n__pycache__/\n")
    for rel, text in (("src/pkg/node.py", "print('hi')\n"), ("courses/c/x.yaml", "a: 1\n")):
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text)
    return root


def test_without_git_a_written_added_removed_or_chmodded_file_shows(tmp_path):
    root = _tree(tmp_path / "course")
    assert "not a git checkout" in not_a_checkout(root)
    before = git_state(root)
    (root / "output").mkdir()
    (root / "output" / "log.txt").write_text("ignored, as git would")
    (root / "src" / "pkg" / "__pycache__").mkdir()
    (root / "src" / "pkg" / "__pycache__" / "node.pyc").write_bytes(b"\0")
    assert git_state(root) == before
    for change in (lambda: (root / "src/pkg/node.py").write_text("print('rewritten')\n"),
                   lambda: (root / "src/pkg/new.py").write_text(""),
                   lambda: os.chmod(root / "src/pkg/node.py", 0o755),
                   lambda: (root / "courses/c/x.yaml").unlink()):
        change()
        after = git_state(root)
        assert after != before
        before = after


def test_the_state_of_one_folder_leaves_the_rest_out(tmp_path):
    root = _tree(tmp_path / "course")
    before = git_state(root, str(root / "courses" / "c"))
    assert "courses/c/x.yaml" in before and "node.py" not in before
    (root / "src" / "pkg" / "node.py").write_text("changed elsewhere")
    assert git_state(root, str(root / "courses" / "c")) == before


def test_a_folder_inside_another_checkout_is_not_one(tmp_path):
    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    root = _tree(tmp_path / "course")
    assert "inside" in not_a_checkout(root)
    assert not_a_checkout(tmp_path) == ""
