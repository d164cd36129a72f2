"""LTI Advantage Assignment and Grade Services 2.0, the tool's side: line items and scores.

- a line item is found in the course context's container (GET lineitems?resource_id=&tag=,
  following `Link: <...>; rel="next"` pages, and matched here too, since a platform may ignore
  the filters) by its resourceId and tag, else created (POST lineitems);
- a score is POSTed to the line item's URL with `/scores` appended to its path (its query kept).

Every request carries the bearer token of course_lti.token; a 401 asks for a new token once.
"""
from __future__ import annotations

import json
import re
import urllib.parse
from typing import Callable, Dict, Mapping, Optional

from course_lti.scores import LineItem
from course_lti.token import TokenSource
from course_lti.transport import Refused, Response, header, json_headers

LINEITEM_TYPE = "application/vnd.ims.lis.v2.lineitem+json"
LINEITEMS_TYPE = "application/vnd.ims.lis.v2.lineitemcontainer+json"
SCORE_TYPE = "application/vnd.ims.lis.v1.score+json"
NEXT_LINK = re.compile(r'<([^>]*)>\s*;[^,]*\brel="?next"?', re.I)
MAX_PAGES = 100


def with_query(url: str, params: Mapping[str, str]) -> str:
    """`url` with `params` added to its query (a platform's container URL may have one already)."""
    parts = urllib.parse.urlsplit(url)
    query = urllib.parse.parse_qsl(parts.query, keep_blank_values=True) + list(params.items())
    return urllib.parse.urlunsplit(parts._replace(query=urllib.parse.urlencode(query)))


def scores_url(lineitem_url: str) -> str:
    """The scores endpoint of a line item: its URL with `/scores` appended to the path."""
    parts = urllib.parse.urlsplit(lineitem_url)
    return urllib.parse.urlunsplit(parts._replace(path=parts.path.rstrip("/") + "/scores"))


def next_page(headers: Mapping[str, str]) -> Optional[str]:
    """The next page's URL a Link header names, if any."""
    found = NEXT_LINK.search(header(headers, "Link"))
    return found.group(1) if found else None


def matches(entry: object, item: LineItem) -> bool:
    """Whether a line item of the container is `item`'s: the same resourceId, and its tag."""
    return (isinstance(entry, dict) and str(entry.get("resourceId", "")) == item.resource_id
            and str(entry.get("tag", "") or "") == item.tag and bool(entry.get("id")))


class AgsClient:
    """Line items and scores of one platform, through a sender that retries (transport.Retrying)."""

    def __init__(self, send: Callable[..., Response], tokens: TokenSource) -> None:
        self._send = send
        self.tokens = tokens

    def _call(self, method: str, url: str, accept: str, content_type: str = "",
              body: Optional[Dict[str, object]] = None) -> Response:
        data = json.dumps(body).encode("utf-8") if body is not None else None
        try:
            return self._send(method, url, json_headers(self.tokens.get(), accept, content_type), data)
        except Refused as err:
            if err.status != 401:
                raise
            self.tokens.forget()  # expired or revoked early: one new token, one more try
            return self._send(method, url, json_headers(self.tokens.get(), accept, content_type), data)

    def find_lineitem(self, container: str, item: LineItem) -> Optional[str]:
        """The URL (id) of `item`'s line item in `container`, None when it has none."""
        url: Optional[str] = with_query(container, {"resource_id": item.resource_id, "tag": item.tag})
        for _ in range(MAX_PAGES):
            if not url:
                break
            response = self._call("GET", url, LINEITEMS_TYPE)
            entries = response.json()
            for entry in entries if isinstance(entries, list) else []:
                if matches(entry, item):
                    return str(entry["id"])
            url = next_page(response.headers)
        return None

    def create_lineitem(self, container: str, item: LineItem) -> str:
        """A new line item for `item`; its URL."""
        response = self._call("POST", container, LINEITEM_TYPE, LINEITEM_TYPE, item.payload())
        created = response.json()
        if not isinstance(created, dict) or not created.get("id"):
            raise Refused("POST", container, response.status, "the new line item has no id")
        return str(created["id"])

    def lineitem(self, container: str, item: LineItem) -> str:
        """`item`'s line item in `container`: found, else created."""
        return self.find_lineitem(container, item) or self.create_lineitem(container, item)

    def post_score(self, lineitem_url: str, score: Dict[str, object]) -> None:
        """One score on a line item."""
        self._call("POST", scores_url(lineitem_url), "application/json", SCORE_TYPE, score)
