#!/usr/bin/env python3
"""Build a Dockerfile without a Docker engine: each instruction replayed in a debootstrap chroot.

`make docker-check` uses it to prove docker/Dockerfile on machines that have only the docker
client (or nothing). It understands the instructions our Dockerfile needs, with Docker's
semantics for the common cases, and refuses any other instruction, naming its line:

- FROM debian:bookworm (or debian:12): `debootstrap --variant=minbase bookworm`, then the chroot
  is prepared by tools/chroot_root.sh (mounts, /etc/hosts, the host's CA certificates and pip
  config), as tools/fresh_debian_check.sh does.
- ENV (`K=V ...` and the legacy `K V`), ARG (`--build-arg` overrides), WORKDIR, USER.
- COPY [--chown=U[:G]] SRC... DEST, honouring .dockerignore (`*`, `**`, `?`, leading `/`, `!`).
- RUN, shell or JSON form, as the current USER (setpriv) with its ENV, ARGs, HOME and WORKDIR.
- CMD is printed; with --run-cmd it is run as the final USER, as `docker run IMAGE` would.

The context is taken once, before the first step, as `docker build` sends it: edits made in the
tree during the build do not reach it. Each step is reported with its time, then PASS or FAIL.
The chroot is removed at the end (unless --keep), on every exit path; a step's output goes to a
log that is kept on failure.

    sudo python3 tools/dockerfile_chroot.py -f docker/Dockerfile [--run-cmd] [--keep] [CONTEXT]

Not emulated: layers and their cache, multi-stage builds, ADD, ENTRYPOINT, EXPOSE and the like.
"""
from __future__ import annotations

import argparse
import json
import os
import posixpath
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, Iterator, List, Optional, Sequence, Tuple

ROOT = Path(__file__).resolve().parents[1]
CHROOT_ROOT = ROOT / "tools" / "chroot_root.sh"
DEFAULT_PATH = "/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin"
BASE_IMAGES = ("debian:bookworm", "debian:12")
INSTRUCTIONS = ("FROM", "ENV", "ARG", "WORKDIR", "COPY", "RUN", "USER", "CMD")
LOG_TAIL_LINES = 15
CONTINUATION = re.compile(r"\\[ \t]*$")


class DockerfileError(Exception):
    """A Dockerfile this tool cannot build, with the line at fault."""


@dataclass(frozen=True)
class Instruction:
    """One instruction: its keyword (upper case), its raw arguments and its first line."""

    line: int
    keyword: str
    args: str

    def describe(self, width: int = 60) -> str:
        text = "%s %s" % (self.keyword, self.args)
        return text if len(text) <= width else text[: width - 3] + "..."


# --- The Dockerfile ---------------------------------------------------------------------------

def parse_dockerfile(text: str) -> List[Instruction]:
    """Instructions of a Dockerfile: comments dropped, `\\` continuations joined as Docker does.

    Comment lines (first non-blank character `#`) are dropped even inside a continuation, and
    so are empty lines there; the continuation's backslash and newline vanish from the text.
    """
    instructions: List[Instruction] = []
    pending: List[str] = []
    start = 0
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        if not pending:
            start = number
        match = CONTINUATION.search(line)
        if match:
            pending.append(line[: match.start()])
            continue
        pending.append(line)
        instructions.append(_instruction(start, "".join(pending)))
        pending = []
    if pending:
        instructions.append(_instruction(start, "".join(pending)))
    return instructions


def _instruction(line: int, text: str) -> Instruction:
    keyword, *args = text.split(None, 1)
    return Instruction(line, keyword.upper(), args[0].strip() if args else "")


def check_instructions(instructions: Sequence[Instruction]) -> None:
    """Fail before any work on an instruction this tool does not build, naming its line."""
    froms = [i for i in instructions if i.keyword == "FROM"]
    for instruction in instructions:
        if instruction.keyword not in INSTRUCTIONS:
            raise DockerfileError("line %d: unsupported instruction %s (this tool builds %s)"
                                  % (instruction.line, instruction.keyword, ", ".join(INSTRUCTIONS)))
    if len(froms) != 1:
        raise DockerfileError("exactly one FROM is supported, found %d" % len(froms))
    before = [i for i in instructions[: instructions.index(froms[0])] if i.keyword != "ARG"]
    if before:
        raise DockerfileError("line %d: %s before FROM" % (before[0].line, before[0].keyword))


def json_form(args: str) -> Optional[List[str]]:
    """The exec (JSON array of strings) form of RUN/CMD/COPY arguments, None for the shell form."""
    if not args.startswith("["):
        return None
    try:
        value = json.loads(args)
    except ValueError:
        return None
    if isinstance(value, list) and all(isinstance(item, str) for item in value):
        return value
    return None


def expand_words(text: str, env: Dict[str, str], split: bool = True) -> List[str]:
    """Docker's word processing for ENV, ARG, WORKDIR, COPY, USER: quotes, `\\`, `$VAR`.

    `$NAME`, `${NAME}`, `${NAME:-word}` and `${NAME:+word}` expand outside single quotes;
    unset names expand to nothing. With split=False whitespace stays inside the one word.
    """
    words: List[str] = []
    word: List[str] = []
    in_word = False
    i = 0
    while i < len(text):
        char = text[i]
        if char in " \t" and split:
            if in_word:
                words.append("".join(word))
                word, in_word = [], False
            i += 1
            continue
        in_word = True
        if char == "\\" and i + 1 < len(text):
            word.append(text[i + 1])
            i += 2
        elif char == "'":
            end = text.find("'", i + 1)
            end = len(text) if end < 0 else end
            word.append(text[i + 1: end])
            i = end + 1
        elif char == '"':
            i = _double_quoted(text, i + 1, env, word)
        elif char == "$":
            i = _variable(text, i, env, word)
        else:
            word.append(char)
            i += 1
    if in_word:
        words.append("".join(word))
    return words


def _double_quoted(text: str, i: int, env: Dict[str, str], word: List[str]) -> int:
    while i < len(text) and text[i] != '"':
        if text[i] == "\\" and i + 1 < len(text) and text[i + 1] in '"$\\':
            word.append(text[i + 1])
            i += 2
        elif text[i] == "$":
            i = _variable(text, i, env, word)
        else:
            word.append(text[i])
            i += 1
    return i + 1


NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _variable(text: str, i: int, env: Dict[str, str], word: List[str]) -> int:
    if text.startswith("${", i):
        end = text.find("}", i)
        if end < 0:
            raise DockerfileError("missing '}' in %r" % text)
        parts = re.fullmatch(r"([A-Za-z_][A-Za-z0-9_]*)(?:(:[-+])(.*))?", text[i + 2: end])
        if parts is None:
            raise DockerfileError("bad substitution %r" % text[i: end + 1])
        name, operator, default = parts.groups()
        value = env.get(name, "")
        if operator == ":-":
            value = value or default
        elif operator == ":+":
            value = default if value else ""
        word.append(value)
        return end + 1
    match = NAME.match(text, i + 1)
    if not match:
        word.append("$")
        return i + 1
    word.append(env.get(match.group(), ""))
    return match.end()


def env_pairs(args: str, env: Dict[str, str]) -> List[Tuple[str, str]]:
    """ENV's `K=V K2="v w"` form, or the legacy `K value with spaces` form."""
    first = args.split(None, 1)
    if not first:
        raise DockerfileError("ENV needs arguments")
    if "=" not in first[0]:
        value = expand_words(first[1], env, split=False) if len(first) > 1 else [""]
        return [(first[0], value[0] if value else "")]
    pairs = []
    for word in expand_words(args, env):
        name, equals, value = word.partition("=")
        if not equals:
            raise DockerfileError("ENV: %r is not NAME=VALUE" % word)
        pairs.append((name, value))
    return pairs


# --- .dockerignore ----------------------------------------------------------------------------

@dataclass(frozen=True)
class IgnorePattern:
    """One .dockerignore line, compiled: Go filepath.Match plus `**`, as moby's patternmatcher."""

    text: str
    exclusion: bool  # a `!` line: re-include what it matches
    regex: "re.Pattern[str]"

    @property
    def literal_prefix(self) -> str:
        return re.split(r"[*?\[\\]", self.text, maxsplit=1)[0]


def compile_pattern(line: str) -> Optional[IgnorePattern]:
    """A .dockerignore line as a pattern; None for comments and blank lines."""
    if line.startswith("#"):
        return None
    text = line.strip()
    exclusion = text.startswith("!")
    if exclusion:
        text = text[1:].strip()
    if not text:
        return None
    text = posixpath.normpath(text).lstrip("/") or "."
    return IgnorePattern(text, exclusion, re.compile(_pattern_regex(text)))


def _pattern_regex(text: str) -> str:
    regex = ["^"]
    i = 0
    while i < len(text):
        char = text[i]
        if text.startswith("**", i):
            i += 2
            if text.startswith("/", i):
                i += 1
            regex.append(".*" if i >= len(text) else "(.*/)?")
            continue
        if char == "*":
            regex.append("[^/]*")
        elif char == "?":
            regex.append("[^/]")
        elif char == "\\" and i + 1 < len(text):
            i += 1
            regex.append(re.escape(text[i]))
        elif char == "[":
            end = text.find("]", i + 2)
            if end < 0:
                regex.append(re.escape(char))
            else:
                regex.append(text[i: end + 1])
                i = end
        else:
            regex.append(re.escape(char))
        i += 1
    regex.append("$")
    return "".join(regex)


@dataclass
class DockerIgnore:
    """The patterns of a .dockerignore: the last pattern matching a path or a parent decides."""

    patterns: List[IgnorePattern] = field(default_factory=list)

    @classmethod
    def parse(cls, text: str) -> "DockerIgnore":
        compiled = (compile_pattern(line) for line in text.lstrip("\ufeff").splitlines())
        return cls([pattern for pattern in compiled if pattern is not None])

    @classmethod
    def for_context(cls, context: Path) -> "DockerIgnore":
        path = context / ".dockerignore"
        return cls.parse(path.read_text()) if path.is_file() else cls()

    def excluded(self, path: str) -> bool:
        """Is `path` (relative to the context, `/`-separated) left out of the build context?"""
        parts = path.strip("/").split("/")
        prefixes = ["/".join(parts[: n]) for n in range(1, len(parts) + 1)]
        result = False
        for pattern in self.patterns:
            if any(pattern.regex.match(prefix) for prefix in prefixes):
                result = not pattern.exclusion
        return result

    def may_include_below(self, directory: str) -> bool:
        """Could an exception pattern bring back something under an excluded directory?"""
        below = directory.strip("/") + "/"
        for pattern in self.patterns:
            prefix = pattern.literal_prefix
            if pattern.exclusion and (prefix.startswith(below) or below.startswith(prefix)):
                return True
        return False


def context_paths(context: Path, ignore: DockerIgnore) -> Iterator[str]:
    """Every path of the build context (files, directories, symlinks), parents first."""
    for current, dirs, files in os.walk(context):
        relative = os.path.relpath(current, context)
        relative = "" if relative == "." else relative + "/"
        kept_dirs = []
        for name in sorted(dirs):
            path = relative + name
            if os.path.islink(context / path):
                files.append(name)
            elif not ignore.excluded(path):
                kept_dirs.append(name)
                yield path
            elif ignore.may_include_below(path):
                kept_dirs.append(name)  # walk on: an exception may bring back a file inside
        dirs[:] = kept_dirs
        for name in sorted(files):
            if not ignore.excluded(relative + name):
                yield relative + name


# --- The chroot -------------------------------------------------------------------------------

@dataclass(frozen=True)
class Account:
    """Who a RUN or CMD runs as, resolved in the chroot's /etc/passwd and /etc/group."""

    uid: int
    gid: int
    home: str


def _table(path: Path) -> List[List[str]]:
    return [line.split(":") for line in path.read_text().splitlines() if line and not line.startswith("#")]


def resolve_account(root: Path, spec: str) -> Account:
    """`name`, `uid`, `name:group` or `uid:gid` as the chroot knows them."""
    user, _, group = spec.partition(":")
    passwd = _table(root / "etc" / "passwd")
    entry = next((row for row in passwd if user in (row[0], row[2])), None)
    if entry is None and not user.isdigit():
        raise DockerfileError("unknown user %r in the chroot" % user)
    uid = int(entry[2]) if entry else int(user)
    gid = int(entry[3]) if entry else 0
    home = entry[5] if entry else "/"
    if group:
        row = next((row for row in _table(root / "etc" / "group") if group in (row[0], row[2])), None)
        if row is None and not group.isdigit():
            raise DockerfileError("unknown group %r in the chroot" % group)
        gid = int(row[2]) if row else int(group)
    return Account(uid, gid, home)


def chroot_root(action: str, root: Path, log: Path) -> None:
    """tools/chroot_root.sh ACTION ROOT (bootstrap, prepare, release), its output in `log`."""
    with log.open("a") as out:
        subprocess.run(["bash", str(CHROOT_ROOT), action, str(root)], stdout=out,
                       stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, check=True)


def run_logged(command: Sequence[str], env: Dict[str, str], log: Path) -> int:
    """Run `command` in its own session, output to `log`; kill its group if we are interrupted."""
    with log.open("a") as out:
        process = subprocess.Popen(list(command), env=env, stdout=out, stderr=subprocess.STDOUT,
                                   stdin=subprocess.DEVNULL, start_new_session=True)
        try:
            return process.wait()
        finally:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()


def kill_processes_in(root: Path) -> None:
    """Kill what is still running inside the chroot (ours: a RUN's daemon), so it unmounts."""
    root = root.resolve()
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            if os.readlink(entry / "root") == str(root):
                os.kill(int(entry.name), signal.SIGKILL)
        except OSError:
            continue


def copy_path(origin: Path, target: Path) -> None:
    """One file, folder (not its contents) or symlink (as a symlink), with its mode and times."""
    if origin.is_symlink():
        os.symlink(os.readlink(origin), target)
    elif origin.is_dir():
        target.mkdir(exist_ok=True)
        shutil.copystat(origin, target)
    else:
        shutil.copy2(origin, target)


def tail(path: Path, lines: int = LOG_TAIL_LINES) -> str:
    if not path.exists():
        return ""
    return "\n".join(path.read_text(errors="replace").splitlines()[-lines:])


# --- The build --------------------------------------------------------------------------------

@dataclass
class ChrootBuild:
    """The state a Dockerfile build carries from one instruction to the next."""

    context: Path
    root: Path
    build_args: Dict[str, str]
    ignore: DockerIgnore
    env: Dict[str, str] = field(default_factory=dict)
    args: Dict[str, str] = field(default_factory=dict)
    workdir: str = "/"
    user: str = "root"
    cmd: Optional[str] = None
    index: Optional[List[str]] = None  # the context's paths, listed at the first COPY

    def variables(self) -> Dict[str, str]:
        return {**self.args, **self.env}

    def step(self, instruction: Instruction, log: Path) -> None:
        handler = getattr(self, "do_" + instruction.keyword.lower())
        handler(instruction.args, log)

    def do_from(self, args: str, log: Path) -> None:
        image = expand_words(args, self.args)
        if not image or image[0] not in BASE_IMAGES or len(image) not in (1, 3):
            raise DockerfileError("FROM %s: only %s is built (debootstrap)" % (args, " or ".join(BASE_IMAGES)))
        chroot_root("bootstrap", self.root, log)
        chroot_root("prepare", self.root, log)

    def do_arg(self, args: str, log: Path) -> None:
        for word in expand_words(args, self.variables()):
            name, equals, default = word.partition("=")
            self.args[name] = self.build_args.get(name, default if equals else "")

    def do_env(self, args: str, log: Path) -> None:
        for name, value in env_pairs(args, self.variables()):
            self.env[name] = value

    def do_user(self, args: str, log: Path) -> None:
        words = expand_words(args, self.variables())
        if len(words) != 1:
            raise DockerfileError("USER takes one user[:group]")
        self.user = words[0]

    def do_workdir(self, args: str, log: Path) -> None:
        words = expand_words(args, self.variables(), split=False)
        self.workdir = posixpath.normpath(posixpath.join(self.workdir, words[0]))
        target = self.inside(self.workdir)
        if not target.exists():
            target.mkdir(parents=True)
            account = resolve_account(self.root, self.user)
            os.chown(target, account.uid, account.gid)

    def do_cmd(self, args: str, log: Path) -> None:
        self.cmd = args

    def do_run(self, args: str, log: Path) -> None:
        status = run_logged(self.command(args), self.run_env(), log)
        if status != 0:
            raise DockerfileError("exit status %d" % status)

    def do_copy(self, args: str, log: Path) -> None:
        words = json_form(args) or expand_words(args, self.variables())
        owner = "0:0"
        while words and words[0].startswith("--"):
            flag, _, value = words.pop(0).partition("=")
            if flag != "--chown":
                raise DockerfileError("COPY %s is not supported" % flag)
            owner = value
        if len(words) < 2:
            raise DockerfileError("COPY needs a source and a destination")
        account = resolve_account(self.root, owner)
        *sources, dest = words
        dest_path = posixpath.normpath(posixpath.join(self.workdir, dest))
        matched = [path for source in sources for path in self.match_source(source)]
        into_dir = dest.endswith("/") or len(matched) > 1
        with log.open("a") as out:
            for source in matched:
                count = self.copy_tree(source, dest_path, into_dir, account)
                out.write("COPY %s -> %s: %d paths\n" % (source or ".", dest_path, count))

    # -- helpers

    def inside(self, path: str) -> Path:
        """The host path of an image path; refused if a symlink in the image leads out of it."""
        target = self.root / path.lstrip("/")
        if target != self.root and not target.parent.resolve().is_relative_to(self.root.resolve()):
            raise DockerfileError("%s leads out of the chroot (an absolute symlink?)" % path)
        return target

    def run_env(self) -> Dict[str, str]:
        account = resolve_account(self.root, self.user)
        return {"PATH": DEFAULT_PATH, "HOME": account.home, **self.variables()}

    def command(self, args: str) -> List[str]:
        """chroot ROOT [setpriv as USER] env --chdir=WORKDIR -- (sh -c ARGS | the JSON argv)."""
        argv = json_form(args) or ["/bin/sh", "-c", args]
        account = resolve_account(self.root, self.user)
        command = ["chroot", str(self.root)]
        if account.uid != 0:
            command += ["/usr/bin/setpriv", "--reuid=%d" % account.uid, "--regid=%d" % account.gid,
                        "--init-groups"]
        return command + ["/usr/bin/env", "--chdir=" + self.workdir, "--"] + argv

    def context_index(self) -> List[str]:
        if self.index is None:
            self.index = list(context_paths(self.context, self.ignore))
        return self.index

    def match_source(self, source: str) -> List[str]:
        """COPY sources in the context: a path, or a glob matched component by component."""
        clean = posixpath.normpath(source).lstrip("/")
        if clean == ".":
            return [""]
        if not re.search(r"[*?\[]", clean):
            if clean not in self.context_index():
                raise DockerfileError("COPY %s: not in the build context (or in .dockerignore)" % source)
            return [clean]
        pattern = re.compile(_pattern_regex(clean))
        found = [path for path in self.context_index() if pattern.match(path)]
        if not found:
            raise DockerfileError("COPY %s: no match in the build context" % source)
        return found

    def copy_tree(self, source: str, dest: str, into_dir: bool, account: Account) -> int:
        """Copy one context path; a directory's contents go into dest, as Docker's COPY does."""
        origin = self.context / source
        if origin.is_dir() and not origin.is_symlink():
            prefix = source + "/" if source else ""
            members = [path for path in self.context_index() if path.startswith(prefix)]
            self.make_dirs(dest, account)
            for path in members:
                self.make_dirs(posixpath.dirname(posixpath.join(dest, path[len(prefix):])), account)
                self.copy_entry(self.context / path, posixpath.join(dest, path[len(prefix):]), account)
            return len(members)
        into_dir = into_dir or (self.inside(dest).is_dir() and not self.inside(dest).is_symlink())
        target = posixpath.join(dest, posixpath.basename(source)) if into_dir else dest
        self.make_dirs(posixpath.dirname(target), account)
        self.copy_entry(origin, target, account)
        return 1

    def make_dirs(self, path: str, account: Account) -> None:
        target = self.inside(path)
        missing = []
        while not target.exists() and target != self.root:
            missing.append(target)
            target = target.parent
        for directory in reversed(missing):
            directory.mkdir()
            os.chown(directory, account.uid, account.gid)

    def copy_entry(self, origin: Path, dest: str, account: Account) -> None:
        target = self.inside(dest)
        if target.is_symlink() or (target.exists() and not target.is_dir()):
            target.unlink()
        copy_path(origin, target)
        os.chown(target, account.uid, account.gid, follow_symlinks=False)


# --- Command line -----------------------------------------------------------------------------

def raise_on_signal(signum: int, frame: object) -> None:
    raise KeyboardInterrupt("signal %d" % signum)


def snapshot_context(context: Path, ignore: DockerIgnore, into: Path) -> Path:
    """The build context as `docker build` sends it: taken once, before the first step, without
    what .dockerignore leaves out, so that edits made in the tree during the build do not race
    its COPY steps (a file that vanishes while it is taken is skipped)."""
    into.mkdir()
    for path in context_paths(context, ignore):
        source, target = context / path, into / path
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            copy_path(source, target)
        except FileNotFoundError:
            continue
    return into


def build(options: argparse.Namespace, instructions: Sequence[Instruction]) -> bool:
    """Every instruction in order, then CMD if asked; True when all passed. Cleans up always."""
    work = Path(tempfile.mkdtemp(prefix="dockerfile-chroot.", dir=options.work_dir))
    root, logs = work / "root", work / "log"
    logs.mkdir()
    ok = False
    try:
        ignore = DockerIgnore.for_context(options.context)
        context = snapshot_context(options.context, ignore, work / "context")
        state = ChrootBuild(context, root, dict(options.build_arg), ignore)
        total = len(instructions) + (1 if options.run_cmd else 0)
        for number, instruction in enumerate(instructions, start=1):
            log = logs / ("%02d-%s.log" % (number, instruction.keyword.lower()))
            if not run_step(state, instruction, number, total, log):
                return False
        if state.cmd is not None and not options.run_cmd:
            print("CMD (not run; --run-cmd runs it as %s): %s" % (state.user, state.cmd))
        ok = not options.run_cmd or run_cmd(state, total, logs / "cmd.log")
        return ok
    finally:
        kill_processes_in(root)
        released = not root.exists() or _released(root, logs)
        if options.keep or not released:
            print("kept: %s" % work if released else "left in place (still mounted): %s" % work)
        elif ok:
            subprocess.run(["rm", "-rf", "--one-file-system", str(work)], check=False)
        else:
            subprocess.run(["rm", "-rf", "--one-file-system", str(root), str(work / "context")], check=False)
            print("logs: %s" % logs)


def run_cmd(state: ChrootBuild, number: int, log: Path) -> bool:
    """The image's CMD as `docker run IMAGE` runs it: as the final USER, in its WORKDIR."""
    if state.cmd is None:
        print("FAIL: --run-cmd but the Dockerfile has no CMD")
        return False
    started = time.monotonic()
    status = run_logged(state.command(state.cmd), state.run_env(), log)
    report(number, number, "run CMD %s as %s" % (state.cmd, state.user), status == 0, time.monotonic() - started)
    print(indent(tail(log)))
    return status == 0


def _released(root: Path, logs: Path) -> bool:
    try:
        chroot_root("release", root, logs / "release.log")
        return True
    except subprocess.CalledProcessError:
        return False


def run_step(state: ChrootBuild, instruction: Instruction, number: int, total: int, log: Path) -> bool:
    started = time.monotonic()
    try:
        state.step(instruction, log)
    except (DockerfileError, subprocess.CalledProcessError, OSError) as error:
        with log.open("a") as out:
            out.write("\n%s: %s\n" % (type(error).__name__, error))
        report(number, total, "line %d %s" % (instruction.line, instruction.describe()), False,
               time.monotonic() - started)
        print(indent(tail(log)))
        return False
    report(number, total, "line %d %s" % (instruction.line, instruction.describe()), True,
           time.monotonic() - started)
    return True


def report(number: int, total: int, what: str, passed: bool, seconds: float) -> None:
    print("%s  step %d/%d  %7.1f s  %s" % ("PASS" if passed else "FAIL", number, total, seconds, what),
          flush=True)


def indent(text: str) -> str:
    return "\n".join("    | " + line for line in text.splitlines())


def build_arg(text: str) -> Tuple[str, str]:
    name, _, value = text.partition("=")
    return name, value


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("context", nargs="?", type=Path, default=ROOT, help="build context (default: this repo)")
    parser.add_argument("-f", "--file", type=Path, help="Dockerfile (default: CONTEXT/Dockerfile)")
    parser.add_argument("--build-arg", action="append", type=build_arg, default=[], metavar="NAME=VALUE")
    parser.add_argument("--run-cmd", action="store_true", help="run CMD as the final USER after the build")
    parser.add_argument("--keep", action="store_true", help="keep the chroot and logs")
    parser.add_argument("--work-dir", default="/var/tmp", help="where the chroot is made (default /var/tmp)")
    parser.add_argument("--dry-run", action="store_true", help="parse and list the steps, build nothing")
    options = parser.parse_args(argv)
    options.context = options.context.resolve()
    dockerfile = options.file or options.context / "Dockerfile"
    try:
        instructions = parse_dockerfile(dockerfile.read_text())
        check_instructions(instructions)
    except DockerfileError as error:
        print("%s: %s" % (dockerfile, error), file=sys.stderr)
        return 2
    if options.dry_run:
        for instruction in instructions:
            print("line %3d  %s %s" % (instruction.line, instruction.keyword, instruction.args))
        return 0
    if os.geteuid() != 0:
        print("dockerfile_chroot: needs root (debootstrap, chroot, mount): sudo make docker-check", file=sys.stderr)
        return 2
    for signum in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, raise_on_signal)
    print("building %s in a debootstrap chroot (context %s)" % (dockerfile, options.context), flush=True)
    started = time.monotonic()
    passed = build(options, instructions)
    print("%s: %s (%.0f s)" % ("PASS" if passed else "FAIL", dockerfile, time.monotonic() - started))
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
