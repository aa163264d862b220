"""The HTTP service (FastAPI) and its web page: :func:`create_app` builds the application, ``objrecall serve``
(:mod:`kb.service.cli.serve`) runs it. Endpoints, authentication and deployment: ``kb/SERVICE.md``.

Modules: ``settings`` (limits, token, error statuses), ``app`` (the app factory and its routes),
``limits`` (body/time limits and security headers, pure ASGI), ``jobs`` (ingestion child processes),
``process`` (running the service in a child process), ``static/`` (the web page). Importing this package
does not import FastAPI; :func:`create_app` does.
"""

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from kb.service.http.app import create_app
    from kb.service.http.process import free_port, serve_subprocess
    from kb.service.http.settings import ERROR_STATUS, MAX_PAGE, ServiceSettings, load_token

__all__ = ["ERROR_STATUS", "MAX_PAGE", "ServiceSettings", "create_app", "free_port", "load_token", "serve_subprocess"]

#: Where each public name lives; imported on first use, so ``objrecall --help`` (which reads
#: ``settings`` for the ``serve`` options) does not load the app and its middleware.
_EXPORTS = {
    "create_app": "app",
    "free_port": "process",
    "serve_subprocess": "process",
    "ERROR_STATUS": "settings",
    "MAX_PAGE": "settings",
    "ServiceSettings": "settings",
    "load_token": "settings",
}


def __getattr__(name: str) -> Any:
    if name not in _EXPORTS:
        raise AttributeError(f"module 'kb.service.http' has no attribute {name!r}")
    value = getattr(importlib.import_module(f"kb.service.http.{_EXPORTS[name]}"), name)
    globals()[name] = value
    return value
