"""Writes need ``Authorization: Bearer <token>`` with the token configured on the server; with none
configured, writes are disabled (403). Reads are open."""

import hmac
from typing import Annotated

from fastapi import Depends, HTTPException
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from kb.errors import WritesDisabled
from kb.service.http.routes import State
from kb.service.http.settings import ENV_TOKEN, ENV_TOKEN_FILE

__all__ = ["require_token"]

bearer = HTTPBearer(auto_error=False, description="The API token configured on the server.")


def require_token(
    creds: Annotated[HTTPAuthorizationCredentials | None, Depends(bearer)],
    state: State,
) -> None:
    """FastAPI dependency of every write route: 403 when writes are disabled, 401 without the right token."""
    token = state.settings.token
    if token is None:
        raise WritesDisabled(
            f"writes are disabled: no API token is configured on the server (set {ENV_TOKEN} or {ENV_TOKEN_FILE})"
        )
    if creds is None or creds.scheme.lower() != "bearer":
        raise HTTPException(
            401, "this endpoint needs 'Authorization: Bearer <token>'", {"WWW-Authenticate": "Bearer"}
        )
    if not hmac.compare_digest(creds.credentials.encode(), token.encode()):
        raise HTTPException(401, "invalid API token", {"WWW-Authenticate": "Bearer"})
