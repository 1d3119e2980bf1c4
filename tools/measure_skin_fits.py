#!/usr/bin/env python3
"""
Measure the skin model's fits to measured skin (``docs/skin-model.md``): the numbers behind its defaults.

    python tools/measure_skin_fits.py calibrate [--every N] [--only NAME]   # background and melanin power, together
    python tools/measure_skin_fits.py calibrate --port-mm 5 [--only NAME]   # the power through the NIST port
    python tools/measure_skin_fits.py calibrate --port-mm 5 --only melanin-power-prior   # the power per subject
    python tools/measure_skin_fits.py calibrate [--port-mm 5] --only melanin-exponential   # the in vivo law's p
    python tools/measure_skin_fits.py background [--every N] [--only NAME]   # the background alone
    python tools/measure_skin_fits.py variants [--every N] [--only NAME,…]   # the alternatives compared
    python tools/measure_skin_fits.py refit [--every N] [--port-mm D] [--power P]   # = skinrender skin --fit
    python tools/measure_skin_fits.py diagnose [--subjects S006,…]   # what the fits on a bound ask for

``calibrate``: the 100 NIST skins fitted with the dermis' scattering held at Jacques 2013's skin average
(a = 46 cm⁻¹) and ``background`` and ``melanin_power`` fitted with melanin, blood, oxygenation and b: the
medians of the fitted background and power are ``BACKGROUND_PER_CM`` and ``MELANIN_POWER`` (two digits).
``calibrate --port-mm 5``: the NIST skins read through their instrument's ~5 mm port (``skinrender.datasets.
port_loss``), water the dermis' only absorber besides blood (background 0), so that the port's lateral loss sets
the scattering's scale: the melanin power fitted with melanin, blood, oxygenation, a and b.
``background``: the same with the melanin power held (at its default, or a variant's spectrum). ``variants``: the full fit (a, b free) at the defaults and under
sourced alternatives (:data:`VARIANTS`, from ``skin_alternatives.py`` beside this file: other absorption levels,
vessel radii, melanin and blood spectra, fat, a Rayleigh part of the scattering, the instrument's lateral loss) —
to show what the fitted parameters follow; ``--only`` picks some by name. ``refit``: the fit at the defaults, the
medians ``SkinParameters``' defaults are taken from. ``diagnose``: named subjects fitted with b
allowed down to −3 (a diagnostic: b < 0 is not physical), then with the melanosome's power law's exponent
changed (its value at 500 nm kept). Each prints medians, ranges, RMS and the bounds hit.
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


def _fit(label, lam, values, names, held, fitted=None, port_mm=None):
    from skinrender.datasets.skin_fit import FIT_PARAMETERS, fit_skin_spectra

    start = time.perf_counter()
    fits = fit_skin_spectra(lam, values, names, workers=None, held=held, fitted=fitted, port_mm=port_mm)
    _summary(label, fits, fitted or FIT_PARAMETERS["adding-doubling"], time.perf_counter() - start)
    return fits


def _apertures(fits) -> None:
    """The fits' median skin read through 5 and 11 mm ports: Takiwaki et al. 2002 measured skin up to ~10 %
    darker at 700 nm through a 5 mm aperture than through an 11 mm one (an independent check of the loss)."""
    import numpy as np

    from skinrender.datasets.skin_fit import measured_reflectance

    names = ("melanin", "blood", "oxygenation", "scattering", "scattering_power")
    median = replace(fits[0].parameters, **{n: float(np.median([getattr(f.parameters, n) for f in fits]))
                                            for n in names})
    lam = np.array([450.0, 500.0, 550.0, 600.0, 650.0, 700.0])
    ratio = measured_reflectance(lam, median, port_mm=5.0) / measured_reflectance(lam, median, port_mm=11.0)
    print("  the median skin through 5 mm over 11 mm: "
          + ", ".join(f"{w:g} nm {r:.3f}" for w, r in zip(lam, ratio)))


def _variant(only: str):
    """``--only``'s one variant ``(label, changes, substitution)`` (none given: no change), or ``None`` after saying
    it is unknown."""
    from skin_alternatives import VARIANTS

    if only and only not in VARIANTS:
        print(f"--only: unknown variant {only!r}; choose from {sorted(VARIANTS)}", file=sys.stderr)
        return None
    return VARIANTS[only] if only else ("", {}, None)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[1])
    parser.add_argument("what", choices=("calibrate", "background", "variants", "refit", "diagnose"))
    parser.add_argument("--subjects", default="S006,S061,S096,S011,S051",
                        help="diagnose: NIST subjects (default: three on b = 0 and two light ones)")
    parser.add_argument("--every", type=int, default=1, help="fit every Nth NIST skin (default 1: all 100)")
    parser.add_argument("--only", default="",
                        help="variants: comma-separated names (default: all); background, calibrate --port-mm: one")
    parser.add_argument("--port-mm", type=float, default=None,
                        help="calibrate, refit: the instrument's sample port diameter, mm (default none); with it "
                             "the background is held at 0 (water only)")
    parser.add_argument("--power", type=float, default=None, help="refit: the melanin power held (default the model's)")
    args = parser.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    sys.path.insert(0, str(ROOT / "tools"))
    from skinrender.datasets import reflectances
    from skinrender.datasets.skin_model import SkinParameters

    if not NIST.exists():
        print(f"{NIST} not found", file=sys.stderr)
        return 2
    measured = reflectances(str(NIST))
    keep = (measured.wavelengths >= 400) & (measured.wavelengths <= 700)
    lam, values = measured.wavelengths[keep], measured.values[::args.every, keep]
    names = measured.names[::args.every]
    if args.what == "calibrate":  # --only: under a variant's substitution, its held changes kept
        from skin_alternatives import substituted

        variant = _variant(args.only)
        if variant is None:
            return 2
        label, changes, substitution = variant
        if args.port_mm is None:  # the scattering's scale from the literature, the background fitted
            title, fixed = "background and melanin power fitted, a held at 46 cm⁻¹", {"scattering": 46.0}
            fitted = ("melanin", "blood", "oxygenation", "scattering_power", "background", "melanin_power")
        else:  # the port's loss sets the scale: water only, a fitted
            title, fixed = f"melanin power fitted through a {args.port_mm:g} mm port, water only", {"background": 0.0}
            fitted = ("melanin", "blood", "oxygenation", "scattering", "scattering_power", "melanin_power")
        held = replace(SkinParameters(), **{k: v for k, v in changes.items()
                                            if k not in ("melanin_power", "port_mm", "background")}, **fixed)
        with substituted(substitution):
            _fit(f"{title} {label}", lam, values, names, held, fitted, args.port_mm)
    elif args.what == "background":  # --only: one variant's substitution (its held changes but the background)
        from skin_alternatives import substituted

        variant = _variant(args.only)
        if variant is None:
            return 2
        label, changes, substitution = variant
        held = replace(SkinParameters(), **{k: v for k, v in changes.items() if k not in ("background", "port_mm")},
                       scattering=46.0)
        with substituted(substitution):
            _fit(f"background fitted, a held at 46 cm⁻¹ {label}", lam, values, names, held,
                 ("melanin", "blood", "oxygenation", "scattering_power", "background"), changes.get("port_mm"))
    elif args.what == "variants":
        from skin_alternatives import VARIANTS, substituted

        chosen = [n for n in args.only.split(",") if n] or list(VARIANTS)
        unknown = sorted(set(chosen) - set(VARIANTS))
        if unknown:
            print(f"--only: unknown variants {unknown}; choose from {sorted(VARIANTS)}", file=sys.stderr)
            return 2
        for name in chosen:
            label, changes, substitution = VARIANTS[name]
            held = replace(SkinParameters(), **{k: v for k, v in changes.items() if k != "port_mm"})
            with substituted(substitution):
                _fit(f"{name}: {label}", lam, values, names, held, port_mm=changes.get("port_mm"))
    elif args.what == "diagnose":
        from skin_alternatives import diagnose

        diagnose(lam, measured.values[:, keep], measured.names, args.subjects.split(","))
    else:
        held = SkinParameters() if args.port_mm is None else replace(SkinParameters(), background=0.0)
        held = held if args.power is None else replace(held, melanin_power=args.power)
        port = "" if args.port_mm is None else f" through a {args.port_mm:g} mm port, water only"
        fits = _fit(f"refit, melanin power {held.melanin_power:g}{port}", lam, values, names, held,
                    port_mm=args.port_mm)
        if args.port_mm is not None:
            _apertures(fits)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
