"""The TF tree from tf2's Buffer.all_frames_as_yaml(), as edges for drawing and as text.

all_frames_as_yaml() maps each child frame to {parent, broadcaster, rate,
most_recent_transform, oldest_transform, buffer_length}; static frames report rate 10000.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, List, Mapping, Set, Tuple

import yaml


@dataclass(frozen=True)
class FrameLink:
    """One child frame and what tf2 knows of the transform from its parent."""

    child: str
    parent: str
    broadcaster: str
    rate_hz: float
    most_recent_s: float


def parse_frames_yaml(text: str) -> List[FrameLink]:
    """Links from all_frames_as_yaml() text; an empty buffer ("[]" or "") gives none."""
    data = yaml.safe_load(text) if text and text.strip() else None
    if not data:
        return []
    if not isinstance(data, Mapping):
        raise ValueError("frames YAML is not a mapping: %r" % (text[:80],))
    links = []
    for child, info in data.items():
        info = info or {}
        links.append(FrameLink(child=str(child), parent=str(info.get("parent", "")),
                               broadcaster=str(info.get("broadcaster", "")),
                               rate_hz=float(info.get("rate", 0.0)),
                               most_recent_s=float(info.get("most_recent_transform", 0.0))))
    return sorted(links, key=lambda link: link.child)


def frames_of(links: List[FrameLink]) -> Set[str]:
    return {link.child for link in links} | {link.parent for link in links if link.parent}


def roots_of(links: List[FrameLink]) -> List[str]:
    """Frames that are nobody's child: the roots of the forest."""
    return sorted(frames_of(links) - {link.child for link in links})


def edge_label(link: FrameLink) -> str:
    rate = "static" if link.rate_hz >= 10000.0 else "%.1f Hz" % link.rate_hz
    return "%s\n%s" % (link.broadcaster, rate)


def tree_edges(links: List[FrameLink]) -> List[Tuple[str, str, str]]:
    return [(link.parent, link.child, edge_label(link)) for link in links if link.parent]


def tree_text(links: List[FrameLink]) -> str:
    """An indented text tree (what the PNG shows), roots first."""
    children: Dict[str, List[str]] = {}
    for link in links:
        children.setdefault(link.parent, []).append(link.child)
    lines: List[str] = []

    def walk(frame: str, depth: int, seen: Set[str]) -> None:
        lines.append("  " * depth + frame)
        for child in sorted(children.get(frame, [])):
            if child not in seen:
                walk(child, depth + 1, seen | {child})

    for root in roots_of(links):
        walk(root, 0, {root})
    return "\n".join(lines) + ("\n" if lines else "")
