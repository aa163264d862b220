"""The one errors module of objrecall.

Every error a user can cause is an :class:`ObjrecallError`; the CLI and the HTTP service turn it into one
clear line (CLI, exit code 1) or a JSON body (HTTP 4xx). Anything else is a bug.

::

    ObjrecallError
    ├── InvalidFeature            a feature value is missing, malformed or absurd (names field and reason)
    ├── CatalogError
    │   ├── ObjectNotFound        no object with that name or alias
    │   └── CatalogImportError    a CSV row was invalid; nothing was imported (names row, column, reason)
    ├── DatabaseError
    │   ├── DatabaseBusy          another process held the database for longer than the busy timeout
    │   ├── CatalogMissing        no catalog file there (one message for every command and the service)
    │   ├── CatalogUnreadable     the file is no DuckDB catalog, or a damaged one (names file and reason)
    │   ├── FolderMissing         the folder a new catalog would be created in does not exist
    │   └── MigrationError        the database could not be brought to the schema head
    ├── QueryRefused              user SQL tried to write, read files, attach, install or load
    ├── QueryFailed               user SQL was valid for the sandbox but failed (syntax, ...)
    │   └── QueryTimeout          user SQL ran past its time limit and was interrupted
    ├── DescriptionError          a description could not be parsed at all (empty input, too long)
    ├── RecallError               recall could not run (empty catalog, unknown metric)
    ├── FetchError                a page could not be fetched (HTTP status, timeout, robots.txt, size cap)
    │   ├── RobotsDisallowed
    │   └── PageTooLarge
    ├── ExtractionError           a page was fetched but holds no usable product record
    │   └── ImpossibleValues      every product value it states was refused (absurd, not positive)
    ├── IngestionError            an ingestion run failed as a whole (the catalog is left as it was)
    ├── SourcesError              a sources.toml file is malformed
    ├── SimulationError           a grasp trial could not be run
    │   └── PhysicsError          the simulation diverged (NaN, MuJoCo warnings): an error, never a result
    └── ServiceError              the HTTP service refuses a request as a whole (kb/service/http/)
        ├── WritesDisabled        a write, but no API token is configured (403)
        ├── IngestionBusy         an ingestion job started by the service is still running (409)
        ├── JobNotFound           no ingestion job with that id (404)
        ├── RenderBusy            as many grasp renders as allowed are running (503, Retry-After)
        └── RequestTimeout        the request or its SQL statement ran past its time limit (504)
"""

from __future__ import annotations

__all__ = [
    "CatalogError",
    "CatalogImportError",
    "CatalogMissing",
    "CatalogUnreadable",
    "DatabaseBusy",
    "DatabaseError",
    "DescriptionError",
    "ExtractionError",
    "FetchError",
    "FolderMissing",
    "IngestionBusy",
    "IngestionError",
    "InvalidFeature",
    "JobNotFound",
    "MigrationError",
    "ObjectNotFound",
    "ObjrecallError",
    "PageTooLarge",
    "PhysicsError",
    "QueryFailed",
    "QueryTimeout",
    "QueryRefused",
    "RecallError",
    "RenderBusy",
    "RequestTimeout",
    "RobotsDisallowed",
    "ServiceError",
    "SimulationError",
    "SourcesError",
    "WritesDisabled",
]


class ObjrecallError(Exception):
    """Base of every error a user can cause; ``str(err)`` is one clear line."""


class InvalidFeature(ObjrecallError, ValueError):
    """A feature value is missing, malformed or absurd."""

    def __init__(self, field: str, value: object, reason: str):
        self.field = field
        self.value = value
        self.reason = reason
        super().__init__(f"{field}={value!r}: {reason}")


class CatalogError(ObjrecallError):
    """A catalog operation failed."""


class ObjectNotFound(CatalogError, LookupError):
    """No object with that name or alias."""

    def __init__(self, name: str, suggestions: tuple[str, ...] = ()):
        self.name = name
        self.suggestions = tuple(suggestions)
        hint = f"; did you mean {' or '.join(repr(s) for s in self.suggestions)}?" if self.suggestions else ""
        super().__init__(f"no object named {name!r} in the catalog{hint}")


class CatalogImportError(CatalogError):
    """A canonical CSV could not be imported; ``problems`` lists (row, column, reason): row 0 is the file as
    a whole (missing, unreadable, not UTF-8), column ``"-"`` a whole row."""

    def __init__(self, path: str, problems: list[tuple[int, str, str]]):
        self.path = path
        self.problems = problems
        first = "; ".join(f"{_where(r, c)}{why}" for r, c, why in problems[:3])
        more = f" (and {len(problems) - 3} more)" if len(problems) > 3 else ""
        super().__init__(f"{path}: nothing imported: {first}{more}")


def _where(row: int, column: str) -> str:
    """"row 3, column mass_g: " of a problem; row 0 is the file as a whole and column "-" the whole row, so
    neither is named ("nothing imported: no such file", "row 4: 3 cells, header has 10")."""
    if row == 0:
        return ""
    return f"row {row}: " if column == "-" else f"row {row}, column {column}: "


class DatabaseError(ObjrecallError):
    """The database file could not be used (missing, read-only, busy)."""


class DatabaseBusy(DatabaseError):
    """Another process held the database for longer than the busy timeout."""


class CatalogMissing(DatabaseError):
    """No catalog file at ``path``: the one message of every command and of the service."""

    def __init__(self, path: object):
        self.path = path
        super().__init__(
            f"{path}: no catalog there (create it with `objrecall init --db {path}`, then `objrecall catalog "
            f"import FILE`; or `objrecall init --seed --db {path}` for the seed catalog)"
        )

    def __reduce__(self):
        return (type(self), (self.path,))


class CatalogUnreadable(DatabaseError):
    """The file at ``path`` is no DuckDB database, a damaged one, or a database without the catalog's
    tables; ``reason`` says which, in the database's own words (:func:`database_reason`)."""

    def __init__(self, path: object, reason: str):
        self.path = path
        self.reason = reason
        super().__init__(f"{path}: not a usable objrecall catalog: {reason}")

    def __reduce__(self):
        return (type(self), (self.path, self.reason))


class FolderMissing(DatabaseError):
    """A new catalog file would be created in a folder that does not exist (never created silently)."""

    def __init__(self, path: object, folder: object):
        self.path = path
        self.folder = folder
        super().__init__(f"{path}: the folder {folder} does not exist (create it first, or give another path)")

    def __reduce__(self):
        return (type(self), (self.path, self.folder))


class MigrationError(DatabaseError):
    """The database could not be brought to the schema head; nothing changed."""


class QueryRefused(ObjrecallError):
    """User SQL tried to write, read files, attach, install or load."""


class QueryFailed(ObjrecallError):
    """User SQL failed (syntax error, time limit, ...)."""


class QueryTimeout(QueryFailed):
    """User SQL ran past its time limit and was interrupted."""


class DescriptionError(ObjrecallError, ValueError):
    """A description could not be parsed at all (not text, too long)."""


class RecallError(ObjrecallError):
    """Recall could not run (empty catalog, unknown metric)."""


class FetchError(ObjrecallError):
    """A page could not be fetched (HTTP status, timeout, size cap, robots.txt)."""

    def __init__(self, url: str, reason: str):
        self.url = url
        self.reason = reason
        super().__init__(f"{url}: {reason}")


class RobotsDisallowed(FetchError):
    """robots.txt forbids fetching the URL."""


class PageTooLarge(FetchError):
    """The page is larger than the size cap; it was not loaded."""


class ExtractionError(ObjrecallError):
    """A page was fetched but holds no usable product record."""


class ImpossibleValues(ExtractionError):
    """Every product value a page states was refused (``refusal``: the first reason, as
    ``scrapers.normalize`` words it: "... is absurd ...", "... is not positive")."""

    def __init__(self, message: str, refusal: str):
        super().__init__(message)
        self.refusal = refusal


class IngestionError(ObjrecallError):
    """An ingestion run failed as a whole; the catalog is as it was."""


class SourcesError(ObjrecallError):
    """A sources file is malformed."""


class SimulationError(ObjrecallError):
    """A grasp trial could not be run."""


class PhysicsError(SimulationError):
    """The simulation diverged (NaN, MuJoCo warnings): an error, never a result."""


class ServiceError(ObjrecallError):
    """The HTTP service refuses a request as a whole."""


class WritesDisabled(ServiceError):
    """A write request, but no API token is configured, so writes are off (HTTP 403)."""


class IngestionBusy(ServiceError):
    """An ingestion job started by the service is still running (HTTP 409)."""


class RenderBusy(ServiceError):
    """As many grasp renders as the service allows at once are running (HTTP 503 with Retry-After)."""

    def __init__(self, message: str, retry_after_s: int = 2):
        super().__init__(message)
        self.retry_after_s = retry_after_s


class JobNotFound(ServiceError):
    """No ingestion job with that id was started by this service (HTTP 404)."""


class RequestTimeout(ServiceError):
    """The request, or its SQL statement, ran past its time limit (HTTP 504)."""
