"""Command-line values that are plainly valid, coerced without building pydantic adapters.

Typer (0.29) coerces every parameter value through a pydantic ``TypeAdapter`` built on first use:
importing pydantic and building the adapters of one command costs about 0.2 s CPU, a fifth of a one-shot
``objrecall recall``. :class:`QuickRuntimeParam` coerces itself only what needs no validation beyond its
type, exactly as Typer's adapters would:

* a ``str`` for a ``str`` parameter, a ``bool`` for a flag (Typer's adapters return them unchanged);
* for an ``int`` or ``float`` parameter without clamping, a Python number of that type (a default) or a
  plain decimal (``12``, ``0.5``), inside the parameter's min and max;
* a path, through ``coerce_cli_path``: the function Typer's own path adapter calls (a non-empty ``str``
  made a ``Path`` first, as pydantic's validator does inside it).

Anything else (another type, a value out of range or written otherwise, lists, choices, files, custom
parsers) goes to Typer's own runtime parameter, built then: errors and unusual values are Typer's own.
:func:`install` makes Typer's parameters use it; ``tests/test_cli_coercion.py`` compares both on every
parameter of every command.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from typer import _coercion, core
from typer._param_types import coerce_cli_path, lenient_issubclass

__all__ = ["QuickRuntimeParam", "install", "quick_runtime_param", "typer_runtime_param"]

#: Typer's own builder (pydantic adapters).
typer_runtime_param = _coercion.build_runtime_param
_INT = re.compile(r"(0|[1-9][0-9]{0,17})\Z")
_FLOAT = re.compile(r"(0|[1-9][0-9]{0,14})(\.[0-9]{1,15})?\Z")
_NOT_PLAIN = object()


@dataclass(frozen=True)
class QuickRuntimeParam(_coercion.RuntimeParam):
    """A plainly valid value coerced here; any other by Typer's own runtime parameter."""

    descriptor: Any = None

    def _coerce_value(self, value: Any, param: Any, ctx: Any) -> Any:
        quick = _plain(self.descriptor, value, param, ctx)
        if quick is not _NOT_PLAIN:
            return quick
        return typer_runtime_param(self.descriptor)._coerce_value(value, param=param, ctx=ctx)


def _number(annotation: Any, value: Any) -> Any:
    if isinstance(value, bool):
        return _NOT_PLAIN
    if annotation is int:
        if isinstance(value, int):
            return value
        return int(value) if isinstance(value, str) and _INT.match(value) else _NOT_PLAIN
    if isinstance(value, int | float) and math.isfinite(value):
        return float(value)
    return float(value) if isinstance(value, str) and _FLOAT.match(value) else _NOT_PLAIN


def _plain(descriptor: Any, value: Any, param: Any, ctx: Any) -> Any:
    info, annotation = descriptor.parameter_info, descriptor.annotation
    if info.parser is not None or descriptor.is_file or descriptor.is_choice:
        return _NOT_PLAIN
    if annotation is str:
        return value if isinstance(value, str) else _NOT_PLAIN
    if annotation is bool:
        return value if isinstance(value, bool) else _NOT_PLAIN
    if annotation in (int, float):
        if getattr(info, "clamp", False):
            return _NOT_PLAIN
        number = _number(annotation, value)
        if number is _NOT_PLAIN or (info.min is not None and number < info.min) or (
                info.max is not None and number > info.max):  # fmt: skip
            return _NOT_PLAIN
        return number
    if descriptor.is_path and isinstance(value, str | os.PathLike):
        path_type = info.path_type or (annotation if lenient_issubclass(annotation, Path) else None)
        if path_type is Path and isinstance(value, str):
            if not value or "\0" in value:
                return _NOT_PLAIN
            value = Path(value)  # what pydantic's Path validator makes of a non-empty str
        try:
            return coerce_cli_path(value, info, path_type=path_type, param=param, ctx=ctx)
        except Exception:  # noqa: BLE001 - Typer's adapter then raises its own error
            return _NOT_PLAIN
    return _NOT_PLAIN


def quick_runtime_param(descriptor: Any) -> Any:
    """:class:`QuickRuntimeParam` for the annotations it knows (str, bool, int, float, paths), else Typer's."""
    plain_type = descriptor.annotation in (str, bool, int, float) or descriptor.is_path
    if descriptor.file_annotation is not None or not plain_type or descriptor.is_list or descriptor.is_tuple:
        return typer_runtime_param(descriptor)
    return QuickRuntimeParam(parameter_info=descriptor.parameter_info, annotation=descriptor.annotation,
                             descriptor=descriptor)  # fmt: skip


def install() -> None:
    """Typer's parameters build their runtime coercion with :func:`quick_runtime_param`."""
    core.build_runtime_param = quick_runtime_param
