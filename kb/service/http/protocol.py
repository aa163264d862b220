"""uvicorn's h11 protocol with a request-read deadline (uvicorn has none of its own).

uvicorn closes an idle keep-alive connection after ``timeout_keep_alive``, but a connection that has sent
part of a request (or nothing at all) stays open for ever: 3,000 half-sent requests held 3,000 sockets.
:class:`RequestReadTimeoutProtocol` starts a deadline when a connection opens and whenever a new request
begins arriving on it; if the request's headers and body are not complete by then, the connection is
closed. Used by ``objrecall serve`` (``--header-timeout``, 10 s by default).
"""

from __future__ import annotations

import asyncio

import h11
from uvicorn.protocols.http.h11_impl import H11Protocol

from kb.service.http.settings import DEFAULT_HEADER_TIMEOUT_S

__all__ = ["DEFAULT_HEADER_TIMEOUT_S", "RequestReadTimeoutProtocol", "protocol_with_timeout"]

_REQUEST_READ = (h11.IDLE, h11.SEND_BODY)  # the client's states while its request is still arriving


class RequestReadTimeoutProtocol(H11Protocol):
    """H11Protocol that closes a connection whose request has not fully arrived within ``read_timeout``."""

    read_timeout: float = DEFAULT_HEADER_TIMEOUT_S

    def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
        self._read_deadline: asyncio.TimerHandle | None = None
        super().connection_made(transport)
        self._arm()

    def data_received(self, data: bytes) -> None:
        super().data_received(data)
        if self.conn.their_state in _REQUEST_READ and not self.transport.is_closing():
            if self._read_deadline is None:
                self._arm()
        else:
            self._disarm()

    def on_response_complete(self) -> None:
        super().on_response_complete()
        self._disarm()  # the keep-alive timer covers the idle time until the next request starts

    def connection_lost(self, exc: Exception | None) -> None:
        self._disarm()
        super().connection_lost(exc)

    def _arm(self) -> None:
        self._disarm()
        self._read_deadline = self.loop.call_later(self.read_timeout, self._read_timed_out)

    def _disarm(self) -> None:
        if getattr(self, "_read_deadline", None) is not None:
            self._read_deadline.cancel()
            self._read_deadline = None

    def _read_timed_out(self) -> None:
        self._read_deadline = None
        if self.conn.their_state in _REQUEST_READ and not self.transport.is_closing():
            self.transport.close()


def protocol_with_timeout(seconds: float) -> type[RequestReadTimeoutProtocol]:
    """The protocol class with its request-read deadline set to ``seconds``."""
    if not seconds > 0:
        raise ValueError(f"header timeout must be > 0 s, got {seconds!r}")
    return type("RequestReadTimeoutProtocol", (RequestReadTimeoutProtocol,), {"read_timeout": float(seconds)})
