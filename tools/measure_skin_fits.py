#!/usr/bin/env python3
"""
Measure the skin model's fits to measured skin (``docs/skin-model.md``): the numbers behind its defaults.

    python tools/measure_skin_fits.py background [--every N]   # the background calibration
    python tools/measure_skin_fits.py variants [--every N]     # the absorption variants compared
    python tools/measure_skin_fits.py refit [--every N]        # = skinrender skin --fit (summary)

``background``: the 100 NIST skins fitted with the dermis' scattering held at Jacques 2013's skin average
(a = 46 cm⁻¹) and ``background`` fitted with melanin, blood, oxygenation and b: the median of the fitted
background is ``BACKGROUND_PER_CM``. ``variants``: the full fit (a, b free) under other absorption choices —
water only (background 0), Jacques 1998's bloodless baseline's red level (0.244 cm⁻¹), one vessel radius, and
epidermal scattering 1.6× — to show what the scattering follows. ``refit``: the fit at the defaults, the
medians ``SkinParameters``' defaults are taken from. Each prints medians, ranges, RMS and the bounds hit.
Needs ``../shared/data/skin_nist.csv`` and the ``skin`` extra; uses every core.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
NIST = ROOT.parent / "shared" / "data" / "skin_nist.csv"


def _summary(label: str, fits, names, seconds: float) -> None:
    import numpy as np

    rms = np.array([f.rms for f in fits])
    print(f"{label}: {len(fits)} fits, {seconds:.0f} s")
    for name in names:
        values = np.array([getattr(f.parameters, name) for f in fits])
        print(f"  {name:18s} median {np.median(values):.4g}  range {values.min():.4g}–{values.max():.4g}")
    hits = [f.bounds_hit for f in fits if f.bounds_hit]
    counts: dict = {}
    for hit in hits:
        for key, side in hit.items():
            counts[f"{key} {side}"] = counts.get(f"{key} {side}", 0) + 1
    print(f"  RMS median {np.median(rms):.4f}, p95 {np.percentile(rms, 95):.4f}, max {rms.max():.4f}; "
          f"{len(hits)} on a bound {counts}; {sum(f.converged for f in fits)} converged")


def _fit(label, lam, values, names, held, fitted=None):
    from skinrender.datasets.skin_fit import FIT_PARAMETERS, fit_skin_spectra

    start = time.perf_counter()
    fits = fit_skin_spectra(lam, values, names, workers=None, held=held, fitted=fitted)
    _summary(label, fits, fitted or FIT_PARAMETERS["adding-doubling"], time.perf_counter() - start)
    return fits


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[1])
    parser.add_argument("what", choices=("background", "variants", "refit"))
    parser.add_argument("--every", type=int, default=1, help="fit every Nth NIST skin (default 1: all 100)")
    args = parser.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    from skinrender.datasets import reflectances
    from skinrender.datasets.skin_model import SkinParameters

    if not NIST.exists():
        print(f"{NIST} not found", file=sys.stderr)
        return 2
    measured = reflectances(str(NIST))
    keep = (measured.wavelengths >= 400) & (measured.wavelengths <= 700)
    lam, values = measured.wavelengths[keep], measured.values[::args.every, keep]
    names = measured.names[::args.every]
    if args.what == "background":
        _fit("background fitted, a held at 46 cm⁻¹", lam, values, names, SkinParameters(scattering=46.0),
             ("melanin", "blood", "oxygenation", "scattering_power", "background"))
    elif args.what == "variants":
        base = SkinParameters()
        for label, held in (("water only (background 0)", replace(base, background=0.0)),
                            ("background 0.244 cm⁻¹ (Jacques 1998's red level)", replace(base, background=0.244)),
                            ("one vessel radius 8 µm", replace(base, vessel_min_um=8.0, vessel_max_um=8.0)),
                            ("epidermal scattering 1.6×", replace(base, epidermis_scattering=1.6))):
            _fit(label, lam, values, names, held)
    else:
        _fit("refit at the defaults", lam, values, names, SkinParameters())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
