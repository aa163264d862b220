"""The HTTP service (FastAPI) and its web page: :func:`create_app` builds the application, ``objrecall serve``
(:mod:`kb.service.cli.serve`) runs it. Endpoints, authentication and deployment: ``kb/SERVICE.md``.

Modules: ``settings`` (limits, token, error statuses), ``app`` (the app factory and its routes),
``limits`` (body/time limits and security headers, pure ASGI), ``jobs`` (ingestion child processes),
``process`` (running the service in a child process), ``static/`` (the web page). Importing this package
does not import FastAPI; :func:`create_app` does.
"""

from kb.service.http.app import create_app
from kb.service.http.process import free_port, serve_subprocess
from kb.service.http.settings import ERROR_STATUS, MAX_PAGE, ServiceSettings, load_token

__all__ = ["ERROR_STATUS", "MAX_PAGE", "ServiceSettings", "create_app", "free_port", "load_token", "serve_subprocess"]
