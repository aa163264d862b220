"""Errors as JSON: every response that is not a success has the body ``{"error": <name>, "detail": <one line>}``.

An :class:`~kb.errors.ObjrecallError` gets the status :func:`~kb.service.http.settings.status_for` gives its
class; a request the schema refuses gets 422 with every problem named; anything else is a bug (500) and
says so without leaking internals.
"""

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from starlette.exceptions import HTTPException as StarletteHTTPException

from kb.errors import DatabaseBusy, ObjrecallError, RenderBusy
from kb.service.http.settings import status_for

__all__ = ["install_error_handlers"]

#: The ``error`` name of each plain HTTP status the framework raises.
HTTP_ERROR_NAMES = {401: "Unauthorized", 403: "Forbidden", 404: "NotFound", 405: "MethodNotAllowed"}


async def objrecall_error(request: Request, err: ObjrecallError) -> JSONResponse:
    headers = None
    if isinstance(err, DatabaseBusy):
        headers = {"Retry-After": "5"}
    elif isinstance(err, RenderBusy):
        headers = {"Retry-After": str(err.retry_after_s)}
    return JSONResponse(
        {"error": type(err).__name__, "detail": " ".join(str(err).split())},
        status_code=status_for(err),
        headers=headers,
    )


async def http_error(request: Request, err: StarletteHTTPException) -> JSONResponse:
    return JSONResponse(
        {"error": HTTP_ERROR_NAMES.get(err.status_code, "HTTPError"), "detail": str(err.detail)},
        status_code=err.status_code,
        headers=getattr(err, "headers", None),
    )


async def validation_error(request: Request, err: RequestValidationError) -> JSONResponse:
    problems = []
    for e in err.errors():
        where = ".".join(str(p) for p in e.get("loc", ()) if p != "body") or "body"
        problems.append(f"{where}: {e.get('msg', 'invalid')}")
    return JSONResponse(
        {"error": "ValidationError", "detail": "; ".join(problems) or "invalid request"}, status_code=422
    )


async def unexpected(request: Request, err: Exception) -> JSONResponse:  # a bug: say so, leak nothing
    return JSONResponse(
        {"error": "InternalError", "detail": f"internal error ({type(err).__name__}); please report it"},
        status_code=500,
    )


def install_error_handlers(app: FastAPI) -> None:
    app.add_exception_handler(ObjrecallError, objrecall_error)
    app.add_exception_handler(StarletteHTTPException, http_error)
    app.add_exception_handler(RequestValidationError, validation_error)
    app.add_exception_handler(Exception, unexpected)
