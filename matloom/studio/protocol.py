"""The studio's request and error conventions (docs/studio-api.md): one-line JSON errors with
their status, and typed readers for the fields of a JSON body.

Every handler reads its body with :func:`read_body` and its fields with the ``need_*`` /
``opt_*`` readers, which raise :class:`ApiError` (400) naming the field; the app turns an
:class:`ApiError` into ``{"error": "..."}`` with its status, so bad input never becomes a 500.
"""

from __future__ import annotations

import json
import math
from typing import Any

from starlette.requests import Request
from starlette.responses import JSONResponse

#: Largest request body (bytes); the security middleware refuses a larger one with 413.
MAX_BODY = 2 * 1024 * 1024
#: Largest image side of an interactive evaluation (``/api/evaluate``, ``/api/compare``).
MAX_EVAL_SIZE = 2048


class ApiError(Exception):
    """A request refused with ``status`` and a one-line message; ``extra`` is merged into the
    JSON reply (e.g. the diagnostics of a program that does not check)."""

    def __init__(self, status: int, message: str, **extra: Any) -> None:
        super().__init__(message)
        self.status = status
        self.message = " ".join(str(message).split()) or "error"
        self.extra = extra

    def response(self) -> JSONResponse:
        return error_response(self.status, self.message, **self.extra)


def error_response(status: int, message: str, **extra: Any) -> JSONResponse:
    """``{"error": message, **extra}`` with ``status`` (and no caching)."""
    return JSONResponse(
        {"error": " ".join(str(message).split()), **extra},
        status_code=status,
        headers={"Cache-Control": "no-store"},
    )


def one_line(err: BaseException) -> str:
    """The first line of an exception's message (the project's errors are one line; a
    ProgramError lists every diagnostic, the first is the one to show)."""
    text = str(err).strip()
    return " ".join(text.splitlines()[0].split()) if text else type(err).__name__


async def read_body(request: Request) -> dict[str, Any]:
    """The JSON object of a request body; 400 when it is not one."""
    raw = await request.body()
    try:
        data = json.loads(raw or b"{}")
    except (json.JSONDecodeError, UnicodeDecodeError) as err:
        raise ApiError(400, f"the body is not JSON: {err}") from None
    except RecursionError:  # arrays or objects nested thousands deep
        raise ApiError(400, "the body is not JSON the studio reads: nested too deep") from None
    if not isinstance(data, dict):
        raise ApiError(400, "the body must be a JSON object")
    _refuse_lone_surrogates(data)
    return data


def _refuse_lone_surrogates(data: Any) -> None:
    """400 when a string of the body holds a lone UTF-16 surrogate (``"\\ud800"``): JSON lets
    one through, but no file, reply or program can hold it."""
    stack = [data]
    while stack:
        item = stack.pop()
        if isinstance(item, str):
            try:
                item.encode("utf-8")
            except UnicodeEncodeError:
                raise ApiError(
                    400, "the body holds text that is not valid Unicode (a lone surrogate)"
                ) from None
        elif isinstance(item, dict):
            stack.extend(item)
            stack.extend(item.values())
        elif isinstance(item, list):
            stack.extend(item)


def need_str(body: dict[str, Any], name: str, *, empty: bool = True) -> str:
    value = body.get(name)
    if not isinstance(value, str):
        raise ApiError(400, f"'{name}' must be a string")
    if not empty and not value.strip():
        raise ApiError(400, f"'{name}' must not be empty")
    return value


def opt_str(body: dict[str, Any], name: str, default: str | None = None) -> str | None:
    value = body.get(name, default)
    if value is not None and not isinstance(value, str):
        raise ApiError(400, f"'{name}' must be a string")
    return value


def opt_int(
    body: dict[str, Any], name: str, default: int, low: int | None = None, high: int | None = None
) -> int:
    value = body.get(name, default)
    if value is None:
        value = default
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float)
        or (isinstance(value, float) and not math.isfinite(value))  # NaN, Infinity
        or value != int(value)
    ):
        raise ApiError(400, f"'{name}' must be a whole number, got {value!r}")
    value = int(value)
    if (low is not None and value < low) or (high is not None and value > high):
        raise ApiError(400, f"'{name}' must be in [{low}, {high}], got {value}")
    return value


def opt_float(body: dict[str, Any], name: str) -> float | None:
    value = body.get(name)
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ApiError(400, f"'{name}' must be a finite number, got {value!r}")
    return float(value)


def opt_bool(body: dict[str, Any], name: str, default: bool = False) -> bool:
    value = body.get(name, default)
    if value is None:
        return default
    if not isinstance(value, bool):
        raise ApiError(400, f"'{name}' must be true or false")
    return value


def opt_list(body: dict[str, Any], name: str, kind: type) -> list[Any]:
    """A list of ``kind`` values (``[]`` when absent)."""
    value = body.get(name) or []
    if not isinstance(value, list) or not all(
        isinstance(v, kind) and not isinstance(v, bool) for v in value
    ):
        raise ApiError(400, f"'{name}' must be a list of {kind.__name__} values")
    return value
