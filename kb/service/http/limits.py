"""The service's outer layer (pure ASGI): request body and time limits, security headers on every response,
the web page's content security policy."""

from __future__ import annotations

import asyncio
import contextlib
import json
from typing import Any

from kb.service.http.settings import ServiceSettings

__all__ = ["PAGE_CSP", "SECURITY_HEADERS", "LimitsMiddleware", "LimitsWrapped", "host_name"]

#: Headers on every response.
SECURITY_HEADERS = ((b"x-content-type-options", b"nosniff"), (b"referrer-policy", b"no-referrer"))
#: The web page's content security policy: its own script and style only, fetches to itself only.
PAGE_CSP = (
    "default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' data:; "
    "connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'self'"
)


def _json_bytes(status: int, error: str, detail: str) -> tuple[list[tuple[bytes, bytes]], bytes]:
    body = json.dumps({"error": error, "detail": detail}).encode()
    headers = [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]
    return headers, body


async def _send_error(send, status: int, error: str, detail: str) -> None:
    headers, body = _json_bytes(status, error, detail)
    await send({"type": "http.response.start", "status": status, "headers": headers})
    await send({"type": "http.response.body", "body": body})


def host_name(header: bytes | None) -> str:
    """The name of a Host header value, without port, lower case (``[::1]:8000`` -> ``::1``)."""
    text = (header or b"").decode("latin-1").strip().lower()
    if text.startswith("["):
        return text[1:].split("]", 1)[0]
    return text.rsplit(":", 1)[0] if text.count(":") == 1 else text


#: Seconds a response whose start was sent before the time limit gets to finish sending its body.
FINISH_GRACE_S = 10.0


class LimitsMiddleware:
    """Pure ASGI middleware: refuse a Host header not in ``allowed_hosts`` (400), bodies over
    ``max_body_bytes`` (413), and answer 504 when the app has not started its response within ``timeout``
    seconds (user SQL is stopped before that, see :mod:`kb.sandbox`)."""

    def __init__(self, app, *, max_body_bytes: int, timeout: float, allowed_hosts: tuple[str, ...] = ("*",)):
        self.app = app
        self.max_body_bytes = max_body_bytes
        self.timeout = timeout
        self.allowed_hosts = frozenset(allowed_hosts)

    @property
    def _too_big(self) -> str:
        return f"request body too large: at most {self.max_body_bytes} bytes"

    def _refusal(self, headers: dict[bytes, bytes]) -> tuple[int, str, str] | None:
        """(status, error, detail) for a request refused on its headers alone: a Host not allowed, or a
        declared body over the limit; None to go on."""
        if "*" not in self.allowed_hosts and host_name(headers.get(b"host")) not in self.allowed_hosts:
            return 400, "BadRequest", "Host header not allowed (see --allowed-host)"
        declared = headers.get(b"content-length")
        if declared is None:
            return None
        try:
            too_big = int(declared) > self.max_body_bytes
        except ValueError:
            return 400, "BadRequest", "invalid Content-Length header"
        return (413, "PayloadTooLarge", self._too_big) if too_big else None

    async def _read_body(self, receive) -> bytes | None:
        """The request body, read up to one chunk past the limit (None when the client disconnects)."""
        chunks: list[bytes] = []
        size = 0
        more = True
        while more:
            message = await receive()
            if message["type"] == "http.disconnect":
                return None
            chunk = message.get("body", b"")
            size += len(chunk)
            chunks.append(chunk)
            if size > self.max_body_bytes:
                break
            more = message.get("more_body", False)
        return b"".join(chunks)

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        refusal = self._refusal(dict(scope.get("headers") or []))
        if refusal is not None:
            await _send_error(send, *refusal)
            return
        # read the whole (small) body first, so a chunked upload cannot exceed the limit either
        body = await self._read_body(receive)
        if body is None:  # the client went away
            return
        if len(body) > self.max_body_bytes:
            await _send_error(send, 413, "PayloadTooLarge", self._too_big)
            return
        replayed = False

        async def replay():
            nonlocal replayed
            if not replayed:
                replayed = True
                return {"type": "http.request", "body": body, "more_body": False}
            return await receive()

        started = False
        extra = list(SECURITY_HEADERS)
        path = scope.get("path", "")
        if path == "/" or path.startswith("/static/"):
            extra.append((b"content-security-policy", PAGE_CSP.encode()))

        async def tracking_send(message):
            nonlocal started
            if message["type"] == "http.response.start":
                started = True
                message = {**message, "headers": [*message.get("headers", []), *extra]}
            await send(message)

        task = asyncio.ensure_future(self.app(scope, replay, tracking_send))
        try:
            await asyncio.wait_for(asyncio.shield(task), timeout=self.timeout)
            return
        except TimeoutError:
            pass
        if started:  # the answer is on its way (a 504 of the route's own included): let it finish, within bounds
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(task, timeout=FINISH_GRACE_S)
            return
        task.cancel()
        with contextlib.suppress(asyncio.CancelledError):
            await task
        if not started:
            await _send_error(
                send, 504, "RequestTimeout", f"the request took longer than the {self.timeout:g} s limit"
            )


class LimitsWrapped:
    """The FastAPI app behind :class:`LimitsMiddleware`; ``.app`` is the FastAPI instance (OpenAPI, state)."""

    def __init__(self, app, settings: ServiceSettings):
        self.app = app
        self.settings = settings
        self._asgi = LimitsMiddleware(
            app, max_body_bytes=settings.max_body_bytes, timeout=settings.request_timeout,
            allowed_hosts=settings.allowed_hosts,
        )

    async def __call__(self, scope, receive, send):
        await self._asgi(scope, receive, send)

    def openapi(self) -> dict[str, Any]:
        return self.app.openapi()

    @property
    def state(self):
        return self.app.state
