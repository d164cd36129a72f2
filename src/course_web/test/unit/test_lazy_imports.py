"""What lab_view does not load until it needs it, each in a fresh interpreter (this one has long
imported everything): Pillow until a picture is asked for, rosservice never (course_web.service_probe
asks a service its type), the mime-type database never for the page's own files. Each costs
resident memory in every student's container (docs/lab_page.md)."""
from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

NODE = Path(__file__).resolve().parents[2] / "nodes" / "lab_view"
WWW = Path(__file__).resolve().parents[2] / "www"
HEAVY = ("PIL", "rosservice", "rosmsg")


def fresh(code: str) -> Any:
    """What `code`, run in a new interpreter, prints as JSON on its last line."""
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_the_node_starts_without_pillow_or_rosservice():
    loaded = fresh("""
        import json, runpy, sys
        runpy.run_path(%r)  # the node's own import path (not run as __main__: main() is not called)
        assert "course_web.app" in sys.modules
        print(json.dumps([name for name in %r if name in sys.modules]))
    """ % (str(NODE), HEAVY))
    assert loaded == []


def test_a_picture_loads_pillow_when_asked_and_is_made():
    found = fresh("""
        import json, sys
        from course_web import frames
        before = "PIL" in sys.modules
        raw = bytes((69, 86, 255)) * 40 * 30
        header, body = frames.unpack(frames.image_frame("/cam", "jpeg", "rgb8", 40, 30, 120, raw, {"secs": 1, "nsecs": 2}))
        print(json.dumps({"before": before, "after": "PIL" in sys.modules, "header": header,
                          "jpeg": body[:2] == b"\\xff\\xd8" and body[-2:] == b"\\xff\\xd9"}))
    """)
    assert found["before"] is False
    assert found["after"] is True
    assert found["jpeg"] is True
    assert found["header"] == {"op": "image", "topic": "/cam", "format": "jpeg", "width": 40, "height": 30,
                               "stamp": {"secs": 1, "nsecs": 2}}


def test_the_pages_files_are_typed_without_the_mime_database_and_others_as_before(tmp_path):
    for name in ("index.html", "main.js", "lab.css", "logo.png", "notes.js.gz"):
        (tmp_path / name).write_bytes(b"x")
    found = fresh("""
        import asyncio, json, mimetypes, socket
        import tornado.httpclient, tornado.httpserver
        from course_web.protocol import Bridge
        from course_web.server import Settings, application

        async def fetch(port, names):
            client = tornado.httpclient.AsyncHTTPClient()
            return [(await client.fetch("http://127.0.0.1:%%d/%%s" %% (port, name))).headers["Content-Type"]
                    for name in names]

        async def scenario():
            with socket.socket() as probe:
                probe.bind(("127.0.0.1", 0))
                port = probe.getsockname()[1]
            server = tornado.httpserver.HTTPServer(application(Settings(Bridge(), %r)))
            server.listen(port, "127.0.0.1")
            try:
                own = await fetch(port, ["index.html", "main.js", "lab.css"])
                inited = mimetypes.inited
                other = await fetch(port, ["logo.png", "notes.js.gz"])
            finally:
                server.stop()
            return {"own": own, "inited": inited, "other": other}
        print(json.dumps(asyncio.run(scenario())))
    """ % str(tmp_path))
    assert found["own"] == ["text/html", "text/javascript", "text/css"]
    assert found["inited"] is False, "serving the page's own files read the mime-type database"
    assert found["other"] == ["image/png", "application/gzip"]


def test_the_page_has_no_file_of_another_kind():
    """The table in course_web.server names every kind of file in www/ (a new kind would read the
    mime-type database again, in every student's lab_view), as the database does."""
    import mimetypes
    from course_web.server import CONTENT_TYPES
    assert {ext: mimetypes.guess_type("page" + ext)[0] for ext in CONTENT_TYPES} == CONTENT_TYPES
    kinds = {path.suffix.lower() for path in WWW.rglob("*") if path.is_file()}
    assert kinds <= set(CONTENT_TYPES), kinds - set(CONTENT_TYPES)
