"""Reading one answer's body: streamed, decoded, under the size cap and the page's deadline.

The body is read in pieces as they arrive (``read1``: at most one socket read each), so the cap and the
deadline are checked while a slow or endless body is still coming. The cap counts decoded bytes (urllib3
decodes gzip and deflate a piece at a time, at most one piece's worth per read, so a decompression bomb is
abandoned as soon as its decoded size passes the cap). Before each read the socket's time-out is set to the
time left (the read time-out, or less near the deadline), so a drip of bytes ends at the deadline. One read
may still loop over several socket reads (a chunk-size line, compressed bytes that decode to nothing yet):
those are ended by the fetch's watchdog (:mod:`scrapers.fetch_watchdog`), which shuts the connection at the
deadline.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

import requests
import urllib3

from kb.errors import FetchError, PageTooLarge
from scrapers.deadlines import PageDeadline
from scrapers.fetch_policy import Clock, FetchPolicy
from scrapers.fetch_records import tagged_error

__all__ = ["read_body"]

_CHUNK = 64 * 1024


def read_body(
    url: str, resp: requests.Response, policy: FetchPolicy, deadline: PageDeadline, clock: Clock
) -> bytes:
    """The whole body of ``resp``, decoded, under ``policy.max_bytes`` (decoded bytes) and ``deadline``.

    Raises :class:`PageTooLarge` (a declared or streamed size over the cap) or :class:`FetchError` (the
    deadline passed: kind ``timeout`` or ``store_budget_spent``; a read time-out; a dropped connection).
    """
    declared = resp.headers.get("Content-Length")
    if declared and declared.strip().isdigit() and int(declared) > policy.max_bytes:
        raise tagged_error(
            PageTooLarge, url, "too_large", f"declared {int(declared)} bytes, over the cap of {policy.max_bytes}"
        )
    chunks: list[bytes] = []
    total = 0

    def time_left() -> float:  # raises when the deadline has passed
        return min(policy.read_timeout_s, deadline.left(url, clock.monotonic()))

    try:
        for chunk in _body_chunks(resp, time_left):
            total += len(chunk)
            if total > policy.max_bytes:
                raise tagged_error(
                    PageTooLarge, url, "too_large", f"body passed the cap of {policy.max_bytes} bytes"
                )
            chunks.append(chunk)
    except (requests.exceptions.ReadTimeout, urllib3.exceptions.ReadTimeoutError, TimeoutError):
        raise _body_timeout(url, deadline, clock) from None
    except requests.exceptions.ConnectionError as err:
        if "timed out" in str(err).lower():
            raise _body_timeout(url, deadline, clock) from None
        raise tagged_error(FetchError, url, "connection_failed", "connection dropped while reading the body") from None
    except (requests.exceptions.RequestException, urllib3.exceptions.HTTPError, OSError) as err:
        raise tagged_error(
            FetchError, url, "connection_failed", f"body could not be read ({type(err).__name__})"
        ) from None
    return b"".join(chunks)


def _body_timeout(url: str, deadline: PageDeadline, clock: Clock) -> FetchError:
    now = clock.monotonic()
    if deadline.passed(now):
        return deadline.error(url, now)
    return tagged_error(FetchError, url, "timeout", "timed out while reading the body")


def _socket(resp: requests.Response):
    """The socket under a streamed urllib3 response, or None (another adapter, a closed connection)."""
    conn = getattr(resp.raw, "connection", None) or getattr(resp.raw, "_connection", None)
    return getattr(conn, "sock", None)


def _body_chunks(resp: requests.Response, time_left: Callable[[], float]) -> Iterator[bytes]:
    """The decoded body in pieces as they arrive; the socket's time-out set to ``time_left()`` (which
    raises once the page's deadline has passed) before each read."""
    raw = resp.raw
    if hasattr(raw, "read1"):
        sock = _socket(resp)
        while True:
            left = time_left()
            if sock is not None:
                sock.settimeout(left)
            chunk = raw.read1(_CHUNK, decode_content=True)
            if not chunk:
                return
            yield chunk
    else:  # an adapter without urllib3 underneath
        for chunk in resp.iter_content(_CHUNK):
            time_left()
            yield chunk
