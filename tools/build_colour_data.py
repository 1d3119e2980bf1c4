#!/usr/bin/env python3
"""
Rebuild the CSVs that skinrender bundles from the colour-science package.

    pip install colour-science==0.4.7
    python tools/build_colour_data.py

Writes, under ``skinrender/datasets/resources/``:

- ``colourchecker_n_ohta.csv``: the 24 patches of
  ``colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"]``, 380–780 nm every 5 nm,
  one column per patch, named as colour-science names them.
- ``camera_nikon_5100_npl.csv`` and ``camera_sigma_sdmerill_npl.csv``:
  ``colour.characterisation.MSDS_CAMERA_SENSITIVITIES["Nikon 5100 (NPL)"]`` and
  ``["Sigma SDMerill (NPL)"]`` (Darrodi et al. 2015), columns R, G, B.
- ``cie1924_photopic.csv``: ``colour.colorimetry.SDS_LEFS_PHOTOPIC["CIE 1924 Photopic Standard Observer"]``,
  the CIE 1924 V(λ), 360–830 nm every 1 nm, one column ``V``.

Every number is written with ``repr`` (the shortest text that reads back as the same
float64), so the bundled sets are bit-identical to colour-science's. Prints the SHA-256
of each file, to paste into ``skinrender/datasets/colour_science.py``.
colour-science is distributed under the BSD-3-Clause licence; see
``resources/LICENCE-colour-science.txt``.
"""

from __future__ import annotations

import csv
import hashlib
from pathlib import Path

import colour
import numpy as np
from colour.characterisation import MSDS_CAMERA_SENSITIVITIES
from colour.colorimetry import SDS_LEFS_PHOTOPIC

ROOT_RESOURCES = Path(__file__).resolve().parents[1] / "skinrender" / "datasets" / "resources"

PHOTOPIC = "CIE 1924 Photopic Standard Observer"

CAMERAS = {"Nikon 5100 (NPL)": "camera_nikon_5100_npl.csv", "Sigma SDMerill (NPL)": "camera_sigma_sdmerill_npl.csv"}


def write(name: str, wl: np.ndarray, columns: list[str], values: np.ndarray) -> None:
    """Write ``values`` (shape ``(n_wl, n_columns)``) beside wavelengths ``wl`` (nm), every float as ``repr``."""
    path = ROOT_RESOURCES / name
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(["wavelength_nm", *columns])
        for i, w in enumerate(wl):
            writer.writerow([repr(float(w)), *(repr(float(v)) for v in values[i])])
    print(f"{name}: {hashlib.sha256(path.read_bytes()).hexdigest()}")


def main() -> None:
    print(f"colour-science {colour.__version__}")
    patches = colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"]
    names = list(patches.keys())
    wl = np.asarray(patches[names[0]].wavelengths, float)
    for name in names:
        assert np.array_equal(np.asarray(patches[name].wavelengths, float), wl), name
    values = np.array([np.asarray(patches[name].values, float) for name in names]).T
    write("colourchecker_n_ohta.csv", wl, names, values)

    for camera, filename in CAMERAS.items():
        msds = MSDS_CAMERA_SENSITIVITIES[camera]
        assert list(msds.labels) == ["red", "green", "blue"], msds.labels
        write(filename, np.asarray(msds.wavelengths, float), ["R", "G", "B"], np.asarray(msds.values, float))

    sd = SDS_LEFS_PHOTOPIC[PHOTOPIC]
    write("cie1924_photopic.csv", np.asarray(sd.wavelengths, float), ["V"], np.asarray(sd.values, float)[:, None])


if __name__ == "__main__":
    main()
