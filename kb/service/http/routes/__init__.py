"""The HTTP service's routes, one FastAPI router per group (the OpenAPI tags): ``service`` (health,
version), ``catalog`` (objects, SQL), ``recall`` (parse, recall), ``grasp`` (plans, stored trials),
``ingestion`` (runs and jobs). Each route gets the app's :class:`~kb.service.http.state.ServiceState`
through the :data:`State` dependency."""

from typing import Annotated

from fastapi import Depends, Request

from kb.service.http.state import ServiceState

__all__ = ["State", "service_state"]


def service_state(request: Request) -> ServiceState:
    """FastAPI dependency: the app's :class:`ServiceState`."""
    return request.app.state.service


State = Annotated[ServiceState, Depends(service_state)]
