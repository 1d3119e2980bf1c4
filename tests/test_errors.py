"""
Tests for :mod:`skinrender.errors`: an error carries its role, flag, cause and hint as fields, so the command line
words it without matching its text; :func:`~skinrender.errors.naming` blames the flag of the argument at fault.
"""

from __future__ import annotations

import pickle

import pytest

from skinrender.errors import SkinrenderError, flag_of, naming


def refuse(**fields):
    raise SkinrenderError("x.csv: measured over 420–680 nm", **fields)


def test_the_hint_is_kept_apart_from_the_message():
    error = SkinrenderError("x.csv: measured over 420–680 nm", cause="coverage", hint="choose another grid")
    assert error.message == "x.csv: measured over 420–680 nm" and str(error).endswith("; choose another grid")


def test_naming_prefixes_the_flag_and_keeps_the_fields():
    with pytest.raises(SkinrenderError) as caught:
        naming("--reflectances", refuse, cause="coverage", hint="choose another grid")
    error = caught.value
    assert error.flag == "--reflectances" and error.cause == "coverage" and error.hint == "choose another grid"
    assert error.message == "--reflectances: x.csv: measured over 420–680 nm"


@pytest.mark.parametrize("role, expected", [("camera", "--camera"), ("illuminant", "--range"), (None, "--count")])
def test_naming_blames_the_argument_at_fault_by_its_role(role, expected):
    """Seen: ``illuminants --range 1 1e9`` and a camera whose responses underflow were blamed on --count."""
    with pytest.raises(SkinrenderError) as caught:
        naming({"camera": "--camera", "illuminant": "--range", None: "--count"}, refuse, role=role)
    assert str(caught.value).startswith(expected + ": ")


def test_an_error_named_already_keeps_its_flag():
    with pytest.raises(SkinrenderError) as caught:
        naming("--camera", naming, "SCENE", refuse)
    assert str(caught.value).startswith("SCENE: ") and caught.value.flag == "SCENE"


def test_an_error_crosses_a_process_boundary_whole():
    """Worker processes send errors back pickled: the fields survive."""
    error = pickle.loads(pickle.dumps(SkinrenderError("m", role="spp", flag="--spp", cause="c", hint="h")))
    assert (error.message, error.role, error.flag, error.cause, error.hint, str(error)) == (
        "m", "spp", "--spp", "c", "h", "m; h")


def test_naming_reads_the_flag_field_never_the_words():
    """An error is named by its fields: one that carries its flag is kept as it is; one whose words merely start
    with a flag's spelling is not taken for named (its text is never matched)."""
    def named(**fields):
        raise SkinrenderError("--spp must be an integer", **fields)

    with pytest.raises(SkinrenderError) as caught:
        naming("--quality", named, flag="--spp")
    assert str(caught.value) == "--spp must be an integer" and caught.value.flag == "--spp"
    with pytest.raises(SkinrenderError) as caught:
        naming("--quality", named)
    assert str(caught.value) == "--quality: --spp must be an integer" and caught.value.flag == "--quality"


def test_flag_of_tells_a_flag_from_an_argument_name():
    assert flag_of("--tolerance") == "--tolerance" and flag_of("tolerance") is None
