"""
Command-line helpers
====================

What every command shares: the help texts, the argument groups (grid,
model, search, render options), printing one JSON document or a text table,
and the grid and render options parsed from the arguments. Choices come from
the method tables of the package (:mod:`skinrender.methods`).
"""

from __future__ import annotations

import argparse
import json
import sys

from ..errors import SkinrenderError

__all__ = [
    "HELP_CAMERA", "HELP_ILLUMINANT", "HELP_GRID", "add_common", "add_grid", "add_model", "add_search",
    "add_render", "emit", "table", "range_text", "grid_of", "render_options", "choices_help",
]

HELP_CAMERA = (
    "camera: 'gbell:N@P1,P2,P3' (sensor N, FWHM N·10 nm, peaks in nm), 'gbell:N,b=B@…', "
    "'impulse@P1,P2,P3', a bundled name (see 'skinrender cameras') or a CSV path "
    "(wavelength nm, R, G, B)"
)
HELP_ILLUMINANT = "kelvin (3300 or 3300K, a Planckian radiator), A (2856 K), H (Horizon, 2300 K) or a CSV path"
HELP_GRID = "integration grid START:END:STEP in nm (default 400:700:1)"


def choices_help(methods: dict) -> str:
    """``name (meaning), …`` of a method table, for a flag's help."""
    return "; ".join(f"{name}: {meaning}" for name, meaning in methods.items()).replace("%", "%%")


def add_common(parser: argparse.ArgumentParser) -> None:
    """``--json``."""
    parser.add_argument("--json", action="store_true", help="print one JSON document on stdout")


def add_grid(parser: argparse.ArgumentParser) -> None:
    """``--grid`` and ``--extrapolation``."""
    from ..spectra import EXTRAPOLATIONS

    parser.add_argument("--grid", default="400:700:1", help=HELP_GRID)
    parser.add_argument("--extrapolation", default="refuse", choices=list(EXTRAPOLATIONS),
                        help="for CSV cameras and reflectances that do not cover the grid: " + choices_help(EXTRAPOLATIONS))


def add_model(parser: argparse.ArgumentParser) -> None:
    """``--normalization`` (``--normalisation`` accepted too) and ``--knee``."""
    from ..model.response import NORMALISATIONS

    parser.add_argument("--normalization", "--normalisation", dest="normalization", default="white",
                        choices=list(NORMALISATIONS), help="illuminant normalisation: " + choices_help(NORMALISATIONS))
    parser.add_argument("--knee", action="store_true", help="apply the knee of Eq. 11 (output ≤ 255)")


def add_search(parser: argparse.ArgumentParser) -> None:
    """The reflectance sets and the executors of the Stage 3 search."""
    parser.add_argument("--skin", default="skin", help="skin reflectance set, name or CSV path (default skin)")
    parser.add_argument("--munsell", default="munsell", help="Munsell reflectance set, name or CSV path (default munsell)")
    parser.add_argument("--workers", type=int, help="processes (default: every core)")
    parser.add_argument("--dask", metavar="ADDRESS", help="run on a Dask cluster (scheduler address, tcp://host:8786)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar on stderr")


def add_render(parser: argparse.ArgumentParser) -> None:
    """The Mitsuba options: quality, spp, sampler, seed, variant, channels."""
    from ..rendering.renderer import CHANNEL_GROUPINGS, QUALITY_PRESETS, SAMPLERS

    parser.add_argument("--quality", choices=list(QUALITY_PRESETS), default="standard",
                        help="preset: " + ", ".join(f"{k} ({v['spp']} spp)" for k, v in QUALITY_PRESETS.items())
                        + "; multijitter sampler; default standard")
    parser.add_argument("--spp", type=int, help="samples per pixel (overrides --quality)")
    parser.add_argument("--sampler", choices=list(SAMPLERS), help="Mitsuba sampler: " + choices_help(SAMPLERS))
    parser.add_argument("--seed", type=int, default=0, help="sampler seed; the same seed gives the same image (default 0)")
    parser.add_argument("--variant", help="force a Mitsuba variant (llvm_ad_spectral, cuda_ad_spectral, scalar_spectral); "
                        "default: the fastest that works here")
    parser.add_argument("--channels", choices=list(CHANNEL_GROUPINGS), default="auto",
                        help="render passes: " + choices_help(CHANNEL_GROUPINGS))


def emit(args: argparse.Namespace, document: dict, text: str) -> None:
    """Print ``document`` as one JSON document (``--json``) or ``text``."""
    if args.json:
        json.dump(document, sys.stdout, indent=2, allow_nan=False)
        sys.stdout.write("\n")
    else:
        sys.stdout.write(text.rstrip("\n") + "\n")


def table(rows: list[list[str]], header: list[str]) -> str:
    """A plain-text table with a header and aligned columns."""
    widths = [max(len(str(r[i])) for r in [header, *rows]) for i in range(len(header))]
    lines = ["  ".join(str(c).ljust(w) for c, w in zip(header, widths))]
    lines.append("  ".join("-" * w for w in widths))
    lines += ["  ".join(str(c).ljust(w) for c, w in zip(row, widths)) for row in rows]
    return "\n".join(lines)


def range_text(values: list) -> str:
    """``400–700 nm / 1`` from ``[start, end, step]``."""
    start, end, step = values
    return f"{start:g}–{end:g} nm" + (f" / {step:g}" if step else "")


def grid_of(args: argparse.Namespace):
    """The :class:`~skinrender.spectra.WavelengthGrid` of ``--grid``."""
    from ..spectra import WavelengthGrid

    return WavelengthGrid.parse(args.grid)


def render_options(args: argparse.Namespace) -> dict:
    """``spp``, ``sampler``, ``seed``, ``variant``, ``channels`` from the render flags."""
    from ..rendering.renderer import QUALITY_PRESETS

    preset = QUALITY_PRESETS[args.quality]
    spp = args.spp if args.spp is not None else preset["spp"]
    if spp < 1:
        raise SkinrenderError(f"--spp must be ≥ 1, got {spp}")
    return {"spp": spp, "sampler": args.sampler or preset["sampler"], "seed": args.seed, "variant": args.variant,
            "channels": args.channels}
