"""
Tests for :mod:`skinrender.toml_tables`: one loader checks a TOML table against a dataclass's fields (their
metadata says what each value must be) and words every refusal alike: the file, the table and the field named.
The three formats that use it (chart scenes, face scenes, imagers) keep their messages: their own tests check them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import pytest

from skinrender.errors import SkinrenderError
from skinrender.toml_tables import KINDS, entry, from_table, read_toml, unknown_keys


@dataclass(frozen=True, kw_only=True)
class Item:
    reflectance: str = field(metadata=entry("string"))
    skin: bool = field(default=False, metadata=entry("boolean"))


@dataclass(frozen=True, kw_only=True)
class Lamp:
    temperature: float = field(metadata=entry("number", low=0.0, high=1e12, open_low=True))
    position: tuple = field(default=(0.0, 0.0, 0.0), metadata=entry("vector"))


@dataclass(frozen=True, kw_only=True)
class File:
    item: tuple = field(metadata=entry("tables", schema=Item, nonempty=True, label="patch"))
    lamp: Lamp = field(metadata=entry("table", schema=Lamp))
    sky: Lamp | None = field(default=None, metadata=entry("table", schema=Lamp))
    columns: int = field(metadata=entry("integer", low=1))
    width: int = field(default=8, metadata=entry("integer", low=1, high=64))
    name: str = field(default="unnamed", metadata=entry("text"))
    size: tuple = field(default=(1.0, 1.0, 1.0), metadata=entry("vector", positive=True, key="size_m"))
    note: object = field(default=None, metadata=entry("any"))
    kept: int = 0  # no metadata: never read from a file


GOOD = {"item": [{"reflectance": "grey:0.5"}], "lamp": {"temperature": 2856}, "columns": 2}


def test_a_good_table_is_made_into_its_dataclass_with_the_defaults():
    made = from_table(File, {**GOOD, "name": "  chart ", "size_m": [1, 2, 3]}, "f.toml")
    assert made.item == (Item(reflectance="grey:0.5"),) and made.lamp == Lamp(temperature=2856.0)
    assert made.sky is None and made.width == 8 and made.name == "chart" and made.size == (1.0, 2.0, 3.0)
    assert isinstance(made.lamp.temperature, float) and made.kept == 0
    assert set(KINDS) == {"any", "integer", "number", "string", "text", "boolean", "vector", "table", "tables"}


@pytest.mark.parametrize("change, message", [
    ({"colour": 1, "kept": 2}, "f.toml: unknown field(s) colour, kept; known: columns, item, lamp, name, note, "
                               "size_m, sky, width"),
    ({"item": []}, "f.toml: needs at least one [[item]] table with a 'reflectance' field"),
    ({"item": None}, "f.toml: needs at least one [[item]] table with a 'reflectance' field"),
    ({"item": [{"reflectance": "x"}, 3]}, "f.toml: patch 2: must be a table"),
    ({"item": [{"skin": True}]}, "f.toml: patch 1: missing field 'reflectance'"),
    ({"item": [{"reflectance": "x", "skin": 1}]}, "f.toml: patch 1: field 'skin' must be true or false, got 1"),
    ({"item": [{"reflectance": 2}]}, "f.toml: patch 1: field 'reflectance' must be a string, got 2"),
    ({"lamp": None}, "f.toml: missing table [lamp]"),
    ({"lamp": 3}, "f.toml: field 'lamp' must be a table [lamp]"),
    ({"lamp": {"temperature": 1, "x": 2}}, "f.toml: [lamp]: unknown field(s) x; known: position, temperature"),
    ({"lamp": {"temperature": 0}}, "f.toml: [lamp]: field 'temperature' must be in (0, 1e+12], got 0"),
    ({"lamp": {"temperature": math.nan}}, "f.toml: [lamp]: field 'temperature' must be a finite number, got nan"),
    ({"lamp": {"temperature": True}}, "f.toml: [lamp]: field 'temperature' must be a finite number, got True"),
    ({"sky": {"temperature": 1, "position": [1, 2]}}, "f.toml: [sky]: field 'position' must be three finite "
                                                       "numbers [x, y, z], got [1, 2]"),
    ({"columns": None}, "f.toml: missing field 'columns'"),
    ({"columns": 1.5}, "f.toml: field 'columns' must be an integer, got 1.5"),
    ({"columns": 0}, "f.toml: field 'columns' must be ≥ 1, got 0"),
    ({"width": 65}, "f.toml: field 'width' must be an integer in [1, 64], got 65"),
    ({"width": False}, "f.toml: field 'width' must be an integer in [1, 64], got False"),
    ({"name": " "}, "f.toml: field 'name' must be a non-empty string, got ' '"),
    ({"size_m": [1, 0, 1]}, "f.toml: field 'size_m' must be three finite numbers > 0, got [1, 0, 1]"),
])
def test_each_refusal_names_the_file_the_table_and_the_field(change, message):
    table = {key: value for key, value in {**GOOD, **change}.items() if value is not None}
    with pytest.raises(SkinrenderError) as error:
        from_table(File, table, "f.toml", role="file")
    assert str(error.value) == message and error.value.role == "file"


def test_the_first_unknown_key_and_the_dataclass_own_checks():
    @dataclass(frozen=True, kw_only=True)
    class Checked:
        a: int = field(default=1, metadata=entry("any", required=True))
        b: int = field(default=2, metadata=entry("any", required=True))

        def __post_init__(self):
            if self.a > self.b:
                raise SkinrenderError(f"a must be ≤ b, got {self.a} > {self.b}")

    with pytest.raises(SkinrenderError, match=r"^x: unknown field 'z' \(expected a, b\)$"):
        from_table(Checked, {"z": 1, "y": 2}, "x", unknown="first")
    with pytest.raises(SkinrenderError, match="^x: missing field 'b'$"):
        from_table(Checked, {"a": 1}, "x")
    with pytest.raises(SkinrenderError, match="^x: a must be ≤ b, got 3 > 2$"):
        from_table(Checked, {"a": 3, "b": 2}, "x")
    assert unknown_keys(Checked, {"z": 1, "a": 1, "y": 2}) == ["z", "y"]


def test_read_toml(tmp_path):
    path = tmp_path / "a.toml"
    path.write_text("a = 1\n[b]\nc = 'd'\n")
    assert read_toml(path, "a test TOML") == {"a": 1, "b": {"c": "d"}}
    path.write_bytes(b"a = '\xff'\n")
    with pytest.raises(SkinrenderError, match=r"a.toml: not a UTF-8 text file \(TOML is text\)"):
        read_toml(path, "a test TOML")
    with pytest.raises(SkinrenderError, match=r"^imager file .*a.toml: not a UTF-8 text file") as caught:
        read_toml(path, "a test TOML", where="imager file", role="imager")
    assert caught.value.role == "imager"
    path.write_text("a = = 1\n")
    with pytest.raises(SkinrenderError, match=r"a.toml: not valid TOML: Invalid value \(at line 1, column 5\)"):
        read_toml(path, "a test TOML")
    with pytest.raises(SkinrenderError, match="a test TOML"):
        read_toml(tmp_path, "a test TOML")  # a folder: refused unread, saying what was expected


def test_an_unknown_kind_is_a_programming_error():
    with pytest.raises(ValueError, match="unknown kind 'float'"):
        entry("float")
