"""
TOML tables read into dataclasses
=================================

The package's TOML formats (chart scenes, face scenes, imagers) are each
described by dataclasses: a field read from a table carries its rule in its
metadata (:func:`entry`): what the value must be, its bounds, a nested table
or array of tables it reads with another dataclass, its TOML key where that
is not the field's name. A field with a default is optional in the file. One
loader, :func:`from_table`, checks a table against such a dataclass and
returns it made; :func:`read_toml` reads the file. Every refusal is one line
that names the file and the field, worded alike for every format.

-   :func:`entry`: a field's rule (``field(metadata=entry(...))``).
-   :data:`KINDS`: what a value may be, name → meaning.
-   :func:`from_table`: a table checked and made into its dataclass.
-   :func:`read_toml`: a TOML file's path and table, bounded and checked.
-   :func:`unknown_keys`: the keys of a table its dataclass does not know.

Examples
--------
>>> from dataclasses import dataclass, field
>>> @dataclass(frozen=True)
... class Lamp:
...     temperature: float = field(metadata=entry("number", low=0.0, high=1e12, open_low=True))
...     name: str = field(default="lamp", metadata=entry("text"))
>>> from_table(Lamp, {"temperature": 2856}, "lamp.toml")
Lamp(temperature=2856.0, name='lamp')
>>> from_table(Lamp, {"temperature": -1}, "lamp.toml")
Traceback (most recent call last):
...
skinrender.errors.SkinrenderError: lamp.toml: field 'temperature' must be in (0, 1e+12], got -1
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

from .errors import SkinrenderError
from .files import TOML_BYTES_MAX, read_input

__all__ = ["KINDS", "entry", "from_table", "read_toml", "unknown_keys"]

KINDS = {
    "any": "anything (the dataclass checks it itself)",
    "integer": "an integer (not true or false), at least low and at most high where given",
    "number": "a finite number (an integer or a float), within low and high where given",
    "string": "a string",
    "text": "a non-empty string, its ends stripped",
    "boolean": "true or false",
    "vector": "three finite numbers [x, y, z] (> 0 with positive)",
    "table": "a table [KEY], read with the dataclass schema",
    "tables": "an array of tables [[KEY]], each read with the dataclass schema (at least one with nonempty)",
}
"""What a field's value may be, name → meaning."""


def entry(kind: str, *, low: float | None = None, high: float | None = None, open_low: bool = False,
          positive: bool = False, schema: type | None = None, nonempty: bool = False, label: str | None = None,
          key: str | None = None, required: bool = False) -> dict:
    """
    The metadata of a dataclass field read from a TOML table: ``field(metadata=entry("integer", low=1))``.

    Parameters
    ----------
    kind
        One of :data:`KINDS`.
    low, high, open_low
        Bounds of an integer or number (``open_low``: the value must exceed ``low``).
    positive
        A vector's numbers must be > 0.
    schema
        The dataclass of a ``table`` or of each of ``tables``.
    nonempty, label
        ``tables`` needs at least one (missing or empty: refused), and what an item is called in the messages
        (``patch 2``; default the key).
    key
        The TOML key, where it is not the field's name.
    required
        The file must give the field even though the dataclass has a default.
    """
    if kind not in KINDS:
        raise ValueError(f"unknown kind {kind!r}")
    return {"toml": {"kind": kind, "low": low, "high": high, "open_low": open_low, "positive": positive,
                     "schema": schema, "nonempty": nonempty, "label": label, "key": key, "required": required}}


def _rules(schema: type) -> list[tuple[dataclasses.Field, dict, str]]:
    """The fields of ``schema`` read from a table: (field, rule, TOML key), in their order."""
    out = []
    for item in dataclasses.fields(schema):
        rule = item.metadata.get("toml")
        if rule is not None:
            out.append((item, rule, rule["key"] or item.name))
    return out


def unknown_keys(schema: type, table: dict) -> list[str]:
    """The keys of ``table`` that ``schema`` does not read, in the table's order."""
    known = {key for _, _, key in _rules(schema)}
    return [key for key in table if key not in known]


def _known(schema: type) -> list[str]:
    return [key for _, _, key in _rules(schema)]


def _bounds(low: float, high: float, open_low: bool) -> str:
    return f"{'(' if open_low else '['}{low:g}, {high:g}]".replace("inf]", "∞)")


def _is_number(value: object) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _value(rule: dict, value, where: str, key: str):
    """``value`` of the field ``key`` checked against ``rule`` (``where``: the table, for the messages)."""
    kind, low, high = rule["kind"], rule["low"], rule["high"]
    at = f"{where}: field {key!r}"
    if kind == "integer":
        if high is not None:  # one message for the type and the bounds
            if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
                raise SkinrenderError(f"{at} must be an integer in [{low}, {high}], got {value!r}")
            return value
        if isinstance(value, bool) or not isinstance(value, int):
            raise SkinrenderError(f"{at} must be an integer, got {value!r}")
        if low is not None and value < low:
            raise SkinrenderError(f"{at} must be ≥ {low}, got {value}")
        return value
    if kind == "number":
        if not _is_number(value) or not math.isfinite(value):
            raise SkinrenderError(f"{at} must be a finite number, got {value!r}")
        low = -math.inf if low is None else low
        high = math.inf if high is None else high
        if value < low or (rule["open_low"] and value == low) or value > high:
            raise SkinrenderError(f"{at} must be in {_bounds(low, high, rule['open_low'])}, got {value!r}")
        return float(value)
    if kind == "string":
        if not isinstance(value, str):
            raise SkinrenderError(f"{at} must be a string, got {value!r}")
        return value
    if kind == "text":
        if not isinstance(value, str) or not value.strip():
            raise SkinrenderError(f"{at} must be a non-empty string, got {value!r}")
        return value.strip()
    if kind == "boolean":
        if not isinstance(value, bool):
            raise SkinrenderError(f"{at} must be true or false, got {value!r}")
        return value
    if kind == "vector":
        ok = isinstance(value, list) and len(value) == 3 and all(_is_number(v) and math.isfinite(v) for v in value)
        if not ok or (rule["positive"] and min(value) <= 0):
            what = "three finite numbers > 0" if rule["positive"] else "three finite numbers [x, y, z]"
            raise SkinrenderError(f"{at} must be {what}, got {value!r}")
        return tuple(float(v) for v in value)
    if kind == "table":
        if not isinstance(value, dict):
            raise SkinrenderError(f"{at} must be a table [{key}]")
        return from_table(rule["schema"], value, f"{where}: [{key}]")
    if kind == "tables":
        return _tables(rule, value, where, key)
    return value


def _tables(rule: dict, value, where: str, key: str) -> tuple:
    schema, label = rule["schema"], rule["label"] or key
    if rule["nonempty"] and (not isinstance(value, list) or not value):
        first = next(name for field, item_rule, name in _rules(schema) if _required(field, item_rule))
        raise SkinrenderError(f"{where}: needs at least one [[{key}]] table with a {first!r} field")
    if not isinstance(value, list):
        raise SkinrenderError(f"{where}: field {key!r} must be [[{key}]] tables")
    items = []
    for number, item in enumerate(value, start=1):
        at = f"{where}: {label} {number}"
        if not isinstance(item, dict):
            raise SkinrenderError(f"{at}: must be a table")
        items.append(from_table(schema, item, at))
    return tuple(items)


def _required(field: dataclasses.Field, rule: dict) -> bool:
    return rule["required"] or (field.default is dataclasses.MISSING and field.default_factory is dataclasses.MISSING)


def from_table(schema: type, table: dict, where: str, unknown: str = "all", role: str | None = None):
    """
    ``table`` checked against the fields of the dataclass ``schema`` (those with :func:`entry` metadata) and made
    into it; ``where`` (the file, and the table in it) starts every refusal.

    Keys the schema does not know are refused first (``unknown``: ``all`` lists them all, sorted, with the known
    ones; ``first`` names the first in the file's order with the expected ones in the schema's order); then each
    field in the schema's order: missing (a field without a default, or ``required``), or a value of another
    kind or out of its bounds. A missing optional field takes its default.

    Raises
    ------
    SkinrenderError
        ``WHERE: unknown field(s) …``, ``WHERE: missing field 'KEY'`` (``missing table [KEY]`` for a table),
        ``WHERE: field 'KEY' must be …, got VALUE``.
    """
    try:
        values = _values(schema, table, where, unknown)
    except SkinrenderError as error:
        raise error.reworded(role=role or error.role) from None
    try:
        return schema(**values)
    except SkinrenderError as error:  # the dataclass's own checks
        raise error.reworded(f"{where}: {error.message}", role=role or error.role) from None


def _values(schema: type, table: dict, where: str, unknown: str) -> dict:
    extra = unknown_keys(schema, table)
    if extra and unknown == "first":
        raise SkinrenderError(f"{where}: unknown field {extra[0]!r} (expected {', '.join(_known(schema))})")
    if extra:
        raise SkinrenderError(f"{where}: unknown field(s) {', '.join(sorted(extra))}; known: "
                              f"{', '.join(sorted(_known(schema)))}")
    values = {}
    for field, rule, key in _rules(schema):
        if key not in table:
            if rule["kind"] == "tables" and rule["nonempty"]:
                _tables(rule, None, where, key)  # refused, naming what an item needs
            if _required(field, rule):
                missing = f"table [{key}]" if rule["kind"] == "table" else f"field {key!r}"
                raise SkinrenderError(f"{where}: missing {missing}")
            continue  # the dataclass's default
        values[field.name] = _value(rule, table[key], where, key)
    return values


def read_toml(path: str | Path, what: str, where: str = "", role: str | None = None) -> dict:
    """
    The table of the TOML file ``path`` (``what`` it should be, for the messages: ``a scene TOML``), read
    bounded (:data:`~skinrender.files.TOML_BYTES_MAX`; a pipe, a device or a huge file refused unread): the
    package's one TOML reader (scenes, face scenes, imagers).

    Parameters
    ----------
    where
        Words put before a refusal's path (``imager file``).
    role
        The refusal's ``role`` (the argument at fault: ``imager``).

    Raises
    ------
    SkinrenderError
        ``PATH: not valid TOML: …``, ``PATH: not a UTF-8 text file (TOML is text)``, or the file's own problem.
    """
    prefix = f"{where} " if where else ""
    try:
        data = read_input(path, TOML_BYTES_MAX, what)
    except SkinrenderError as error:
        if not where and role is None:
            raise
        raise error.reworded(prefix + error.message, role=role) from None
    try:
        return tomllib.loads(data.decode("utf-8"))
    except UnicodeDecodeError:
        raise SkinrenderError(f"{prefix}{path}: not a UTF-8 text file (TOML is text)", role=role) from None
    except tomllib.TOMLDecodeError as error:
        raise SkinrenderError(f"{prefix}{path}: not valid TOML: {' '.join(str(error).split())}", role=role) from None
