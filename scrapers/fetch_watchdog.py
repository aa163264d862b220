"""The page deadline's watchdog: a fetch's connection is shut when its deadline passes, whatever it waits for.

A socket time-out bounds one wait for bytes (one ``recv``), never their sum. Clamping it to the time left
bounds a drip only where each read is ours (the body, :mod:`scrapers.fetch_body`); http.client reads the
status line, each header line and each chunk-size line with ``readline``, which loops over ``recv`` until
the line ends (up to 64 KiB a line, 100 header lines), so a server that drips one of them a byte every
50 ms held a fetch as long as it dripped, deadline or not (issue 25). urllib3 and requests offer no total
deadline (``Timeout(total=...)`` still bounds each wait), so a :class:`Watchdog` armed for one exchange
shuts the sockets of that exchange when the deadline passes (``shutdown(SHUT_RDWR)``: a blocked ``recv``
returns at once, from any thread), and the fetcher then discards whatever the cut exchange gave (a
truncated body, partial headers, a dropped connection) and raises the deadline's error.

The sockets are handed over by the transport: :class:`WatchedAdapter`, a requests ``HTTPAdapter`` whose
urllib3 pools make connections that give each socket they open (before any TLS handshake) and each socket
they send a request on (a kept-alive one) to the watchdog armed on the calling thread; with no watchdog
armed they behave exactly as urllib3's. :func:`watch_session` mounts it on a session whose adapters are
requests' stock ones (another adapter, such as a test's, is left alone: its fetches are bounded per read
only). The watchdog keeps a duplicate of each socket's descriptor, so it never shuts a descriptor that was
closed and reused meanwhile, and closes the duplicates when the exchange ends.
"""

from __future__ import annotations

import socket
import threading
from typing import Any

import requests
from requests.adapters import HTTPAdapter
from urllib3.connection import HTTPConnection, HTTPSConnection
from urllib3.connectionpool import HTTPConnectionPool, HTTPSConnectionPool

__all__ = ["Watchdog", "WatchedAdapter", "watch_session"]

_armed = threading.local()


class Watchdog:
    """Shuts the sockets handed to it (:meth:`watch`) ``seconds`` after it is entered; ``fired`` says it did.

    ``with Watchdog(left) as dog:`` arms it on the current thread for the exchange inside the block.
    """

    def __init__(self, seconds: float) -> None:
        self.seconds = seconds
        self.fired = False
        self._lock = threading.Lock()
        self._socks: list[socket.socket] = []
        self._timer = threading.Timer(max(seconds, 0.0), self._fire)
        self._timer.daemon = True
        self._outer: Watchdog | None = None

    def __enter__(self) -> Watchdog:
        self._outer = getattr(_armed, "dog", None)
        _armed.dog = self
        self._timer.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._timer.cancel()
        _armed.dog = self._outer
        with self._lock:
            socks, self._socks = self._socks, []
        for sock in socks:
            sock.close()

    def watch(self, sock: socket.socket) -> None:
        """Watch ``sock`` (through a duplicate of its descriptor); shut it at once if the deadline has passed."""
        fd = sock.fileno()  # the calling thread owns the socket: it is not closed meanwhile
        if fd < 0:  # closed, or detached into a TLS socket (watched as that)
            return
        dup = socket.fromfd(fd, sock.family, sock.type)
        with self._lock:
            self._socks.append(dup)
            fired = self.fired
        if fired:
            _shut(dup)

    def _fire(self) -> None:
        with self._lock:
            self.fired = True
            socks = list(self._socks)
        for sock in socks:
            _shut(sock)


def _shut(sock: socket.socket) -> None:
    try:
        sock.shutdown(socket.SHUT_RDWR)
    except OSError:  # already closed by the peer or by us
        pass


def _watch(sock: socket.socket | None) -> None:
    dog: Watchdog | None = getattr(_armed, "dog", None)
    if dog is not None and sock is not None:
        dog.watch(sock)


class _WatchedMixin:
    """Hands the connection's sockets to the watchdog armed on the calling thread."""

    sock: Any

    def _new_conn(self) -> socket.socket:
        sock = super()._new_conn()  # type: ignore[misc]
        _watch(sock)  # before a TLS handshake, which reads with the socket time-out too
        return sock

    def request(self, *args: Any, **kwargs: Any) -> None:
        _watch(self.sock)  # a kept-alive connection (a new one is watched as it connects)
        super().request(*args, **kwargs)  # type: ignore[misc]


class _WatchedHTTPConnection(_WatchedMixin, HTTPConnection):
    pass


class _WatchedHTTPSConnection(_WatchedMixin, HTTPSConnection):
    pass


class _WatchedHTTPPool(HTTPConnectionPool):
    ConnectionCls = _WatchedHTTPConnection


class _WatchedHTTPSPool(HTTPSConnectionPool):
    ConnectionCls = _WatchedHTTPSConnection


_POOLS = {"http": _WatchedHTTPPool, "https": _WatchedHTTPSPool}


class WatchedAdapter(HTTPAdapter):
    """requests' ``HTTPAdapter`` whose connections hand their sockets to the armed :class:`Watchdog`."""

    def init_poolmanager(self, *args: Any, **kwargs: Any) -> None:
        super().init_poolmanager(*args, **kwargs)
        self.poolmanager.pool_classes_by_scheme = dict(_POOLS)

    def proxy_manager_for(self, proxy: str, **proxy_kwargs: Any) -> Any:
        manager = super().proxy_manager_for(proxy, **proxy_kwargs)
        manager.pool_classes_by_scheme = dict(_POOLS)
        return manager


#: Hosts a session keeps connections to at once (the nightly job crawls up to 16 stores side by side).
HOSTS_AT_ONCE = 16


def watch_session(session: requests.Session) -> None:
    """Mount :class:`WatchedAdapter` for http:// and https:// on ``session`` where its adapter is requests'
    stock one (keeping its pool sizes, at least :data:`HOSTS_AT_ONCE` pools, and its retries); any other
    adapter is left as it is."""
    for prefix in ("http://", "https://"):
        adapter = session.adapters.get(prefix)
        if type(adapter) is not HTTPAdapter:
            continue
        session.mount(
            prefix,
            WatchedAdapter(
                # one pool per host the nightly job crawls at once (scrapers.crawl.MAX_CRAWLING), so no
                # store loses its kept-alive connection to another's
                pool_connections=max(adapter._pool_connections, HOSTS_AT_ONCE),
                pool_maxsize=adapter._pool_maxsize,
                max_retries=adapter.max_retries,
                pool_block=adapter._pool_block,
            ),
        )
        adapter.close()
