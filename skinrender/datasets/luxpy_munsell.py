"""
Munsell 1269 (Joensuu) from luxpy
=================================

The 1269 matte Munsell chips measured at the University of Joensuu (now
University of Eastern Finland), 380–800 nm every 1 nm — the set the paper's
group used. Read from the data file that the installed ``luxpy`` package ships
(``luxpy/data/rfls/Munsell1269.dat``, one row per wavelength), without importing
luxpy's code and without copying the data into this repository.

References
----------
-   :cite:`Parkkinen1989` : Parkkinen, J. P. S., Hallikainen, J., & Jaaskelainen,
    T. (1989). Characteristic spectra of Munsell colors. JOSA A, 6(2), 318–322.
-   :cite:`Smet2015` : Smet, K. A. G. luxpy (GPLv3 package, data file read only).
"""

from __future__ import annotations

import csv
import importlib.util
from pathlib import Path

import numpy as np

from ..extras import require
from .registry import REGISTRY_REFLECTANCES, SpectralSet, register

__all__ = ["sds_munsell_joensuu", "path_luxpy_rfls"]

SOURCE_MUNSELL = (
    "1269 matte Munsell chips measured at Joensuu (Parkkinen et al. 1989, JOSA A 6:318), "
    "file luxpy/data/rfls/Munsell1269.dat of the installed luxpy package"
)
LICENCE_MUNSELL = "luxpy package data (GPLv3 package; data free for research); read in place, not redistributed"


def path_luxpy_rfls() -> Path:
    """Folder of luxpy's reflectance data files, found without importing luxpy."""
    require("munsell", "the 'munsell' set (read from the luxpy package)")
    spec = importlib.util.find_spec("luxpy")
    return Path(spec.origin).parent / "data" / "rfls"


@register(REGISTRY_REFLECTANCES, "munsell", SOURCE_MUNSELL, LICENCE_MUNSELL)
def sds_munsell_joensuu() -> SpectralSet:
    """The 1269 Munsell chips, 380–800 nm every 1 nm, named by their Munsell notation."""
    root = path_luxpy_rfls()
    data = np.loadtxt(root / "Munsell1269.dat", delimiter=",")
    names: list[str] = []
    with (root / "Munsell1269NotationInfo.dat").open(newline="") as handle:
        reader = csv.reader(handle)
        header = next(reader)
        column = {label: i for i, label in enumerate(header)}
        for row in reader:
            names.append(f"{row[column['H']]} {float(row[column['V']]):g}/{float(row[column['C']]):g}")
    if len(names) != data.shape[1] - 1:
        names = [f"munsell {i + 1:04d}" for i in range(data.shape[1] - 1)]
    return SpectralSet("munsell", data[:, 0], data[:, 1:].T.copy(), tuple(names), SOURCE_MUNSELL, LICENCE_MUNSELL)
