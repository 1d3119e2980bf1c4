#!/usr/bin/env python3
"""
Rebuild the ``skin-model`` reflectance set that skinrender bundles, from the skin model itself.

    pip install 'skinrender[skin]'
    python tools/build_skin_model.py

Writes ``skinrender/datasets/resources/skin_model.csv``: the default skin model
(:mod:`skinrender.datasets.skin_model`, adding-doubling) at the 12 melanin
volume fractions of ``MELANIN_FRACTIONS`` (0.01 to 0.5), the other parameters
at their defaults, 400–700 nm every 1 nm, 7 significant digits; and writes its
SHA-256 into ``SHA256_SKIN_MODEL`` of ``skinrender/datasets/skin_model.py``.
The test ``tests/datasets/test_skin_model.py`` checks that the file equals the
model computed afresh.
"""

from __future__ import annotations

import csv
import hashlib
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ROOT_RESOURCES = ROOT / "skinrender" / "datasets" / "resources"
MODULE = ROOT / "skinrender" / "datasets" / "skin_model.py"


def main() -> None:
    import sys

    sys.path.insert(0, str(ROOT))
    from skinrender.datasets.skin_model import skin_model_spectra

    wavelengths, values, names = skin_model_spectra()
    path = ROOT_RESOURCES / "skin_model.csv"
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(["wavelength_nm", *names])
        for i, w in enumerate(wavelengths):
            writer.writerow([f"{w:g}", *(f"{v:.7g}" for v in values[:, i])])
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    text = MODULE.read_text(encoding="utf-8")
    MODULE.write_text(re.sub(r'SHA256_SKIN_MODEL = "[0-9a-f]{64}"', f'SHA256_SKIN_MODEL = "{digest}"', text),
                      encoding="utf-8")
    print(f"{path.name}: {digest} ({len(names)} spectra, {len(wavelengths)} wavelengths)")


if __name__ == "__main__":
    main()
