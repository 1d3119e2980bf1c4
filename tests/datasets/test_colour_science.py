"""Tests for :mod:`skinrender.datasets.colour_science`: the bundled CSVs equal colour-science's own data, bit for bit,
and loading them does not import colour."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import skinrender.datasets as datasets
from skinrender.datasets.colour_science import BUNDLED_CAMERAS, path_colour_rawtoaces, photopic_v_cie1924


def test_macbeth_is_colour_sciences_ohta_chart():
    colour = pytest.importorskip("colour")
    patches = colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"]
    chart = datasets.reflectances("macbeth")
    assert chart.names == tuple(patches.keys())
    for name, values in zip(chart.names, chart.values):
        np.testing.assert_array_equal(chart.wavelengths, patches[name].wavelengths)
        np.testing.assert_array_equal(values, patches[name].values)  # exact: the CSV holds each float's repr


@pytest.mark.parametrize("name", BUNDLED_CAMERAS)
def test_bundled_cameras_are_colour_sciences(name):
    characterisation = pytest.importorskip("colour.characterisation")
    msds = characterisation.MSDS_CAMERA_SENSITIVITIES[name]
    camera = datasets.camera_sensitivities(name)
    assert list(msds.labels) == ["red", "green", "blue"] and camera.names == ("R", "G", "B")
    np.testing.assert_array_equal(camera.wavelengths, msds.wavelengths)
    np.testing.assert_array_equal(camera.values, np.asarray(msds.values).T)


def test_photopic_v_is_colour_sciences_cie1924():
    """V(λ), which every command working in lux uses, bundled bit for bit."""
    colorimetry = pytest.importorskip("colour.colorimetry")
    sd = colorimetry.SDS_LEFS_PHOTOPIC["CIE 1924 Photopic Standard Observer"]
    v = photopic_v_cie1924()
    np.testing.assert_array_equal(v.wavelengths, sd.wavelengths)
    np.testing.assert_array_equal(v.values[0], sd.values)


def test_rawtoaces_folder_is_the_one_colour_names():
    aces_it = pytest.importorskip("colour.characterisation.aces_it")
    assert path_colour_rawtoaces().samefile(aces_it.ROOT_RESOURCES_RAWTOACES)


def test_loading_the_sets_does_not_import_colour():
    """The chart, every colour-science camera and V(λ) (lux) load in a fresh interpreter that never imports
    colour."""
    code = (
        "import sys, skinrender.datasets as d; d.reflectances('macbeth'); "
        "[d.camera_sensitivities(n) for n in ('Nikon 5100 (NPL)', 'Sigma SDMerill (NPL)', 'Canon EOS 5D Mark II')]; "
        "from skinrender.model.exposure import illuminance_lux; illuminance_lux([1.0] * 81, '380:780:5'); "
        "print(sorted(m for m in sys.modules if m == 'colour' or m.startswith('colour.')))"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "[]"


def test_rebuild_script_matches(tmp_path):
    """tools/build_colour_data.py rebuilds the bundled CSVs byte for byte from the installed colour-science."""
    pytest.importorskip("colour")
    import importlib.util
    from pathlib import Path

    from skinrender.datasets.registry import ROOT_RESOURCES

    script = Path(__file__).resolve().parents[2] / "tools" / "build_colour_data.py"
    spec = importlib.util.spec_from_file_location("build_colour_data", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.ROOT_RESOURCES = tmp_path
    module.main()
    for name in ("colourchecker_n_ohta.csv", "cie1924_photopic.csv",
                 *(filename for filename, _ in BUNDLED_CAMERAS.values())):
        assert (tmp_path / name).read_bytes() == (ROOT_RESOURCES / name).read_bytes(), name


def test_licence_file_states_source_version_and_licence():
    from skinrender.datasets.colour_science import VERSION_COLOUR
    from skinrender.datasets.registry import ROOT_RESOURCES

    text = (ROOT_RESOURCES / "LICENCE-colour-science.txt").read_text(encoding="utf-8")
    assert f"colour-science Python package {VERSION_COLOUR}" in text.replace("\n", " ")
    assert "Redistribution and use in source and binary forms" in text  # the BSD-3-Clause text itself
