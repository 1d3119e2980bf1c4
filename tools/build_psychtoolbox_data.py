#!/usr/bin/env python3
"""
Rebuild the CSVs that skinrender bundles from Debian's ``psychtoolbox-3-common``.

    apt-get install psychtoolbox-3-common
    python tools/build_psychtoolbox_data.py

Writes, under ``skinrender/datasets/resources/``:

- ``vrhel_surfaces.csv``: the 170 surfaces of ``sur_vrhel.mat`` (Vrhel, Gershon &
  Iwan 1994), 390–730 nm every 2 nm, one column per surface, named
  ``"<index> <label>"`` with the label from ``labels_vrhel``.
- ``nickerson_munsell.csv``: the 462 Munsell papers of ``sur_nickerson.mat``
  (Nickerson), 380–780 nm every 5 nm.
- ``camera_kodak_dcs200.csv``: ``T_DCS200.mat``, the Kodak DCS-200 RGB
  sensitivities, 380–780 nm every 5 nm.

and prints the SHA-256 of each, to paste into ``skinrender/datasets/psychtoolbox.py``.
Psychtoolbox-3 is distributed under the MIT (Expat) licence; see
``resources/LICENCE-psychtoolbox.txt``.
"""

from __future__ import annotations

import csv
import hashlib
from pathlib import Path

import numpy as np
import scipy.io

ROOT_PSYCHTOOLBOX = Path("/usr/share/psychtoolbox-3/PsychColorimetricData/PsychColorimetricMatFiles")
ROOT_RESOURCES = Path(__file__).resolve().parents[1] / "skinrender" / "datasets" / "resources"


def wavelengths(s_vector: np.ndarray) -> np.ndarray:
    """Psychtoolbox's S = [start, step, count] to wavelengths in nm."""
    start, step, count = (int(v) for v in np.ravel(s_vector))
    return start + step * np.arange(count)


def write(name: str, wl: np.ndarray, columns: list[str], values: np.ndarray, digits: int) -> None:
    path = ROOT_RESOURCES / name
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(["wavelength_nm", *columns])
        for i, w in enumerate(wl):
            writer.writerow([f"{w:g}", *(f"{v:.{digits}g}" for v in values[i])])
    print(f"{name}: {hashlib.sha256(path.read_bytes()).hexdigest()}")


def main() -> None:
    vrhel = scipy.io.loadmat(ROOT_PSYCHTOOLBOX / "sur_vrhel.mat")
    labels = [
        str(entry[0][0][0][0]).replace("\xa0", " ").strip() for entry in vrhel["labels_vrhel"][0]
    ]
    names = [f"{i + 1:03d} {label}" for i, label in enumerate(labels)]
    write("vrhel_surfaces.csv", wavelengths(vrhel["S_vrhel"]), names, vrhel["sur_vrhel"], 6)

    nickerson = scipy.io.loadmat(ROOT_PSYCHTOOLBOX / "sur_nickerson.mat")
    values = np.asarray(nickerson["sur_nickerson"], dtype=np.float64)
    names = [f"nickerson {i + 1:03d}" for i in range(values.shape[1])]
    write("nickerson_munsell.csv", wavelengths(nickerson["S_nickerson"]), names, values, 6)

    dcs = scipy.io.loadmat(ROOT_PSYCHTOOLBOX / "T_DCS200.mat")
    values = np.asarray(dcs["T_DCS200"], dtype=np.float64).T
    write("camera_kodak_dcs200.csv", wavelengths(dcs["S_DCS200"]), ["R", "G", "B"], values, 8)


if __name__ == "__main__":
    main()
