"""
The skin model: ``skin``.

``skinrender skin --melanin M --blood B … [--method …] --json`` prints the model's reflectance and the layers it
is computed from; ``skinrender skin --fit FILE.csv`` fits the model to every column of a reflectance table.
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from ..errors import SkinrenderError
from ..files import write_output
from .common import add_common, check_output, emit, flag, integer_in, table

PARAMETER_FLAGS = {
    "melanin": ("--melanin", "melanosome volume fraction of the epidermis, in [0, 1]"),
    "blood": ("--blood", "blood volume fraction of the dermis, in [0, 1]"),
    "oxygenation": ("--oxygenation", "oxygen saturation of the haemoglobin, in [0, 1]"),
    "scattering": ("--scattering", "reduced scattering coefficient μs' at 500 nm of both layers, cm⁻¹ (> 0)"),
    "scattering_power": ("--scattering-power", "power b of μs' = a (λ/500 nm)^-b, in [0, 4]"),
    "epidermis_mm": ("--epidermis-mm", "thickness of the epidermis, mm (> 0)"),
    "n": ("--n", "refractive index of both layers (≥ 1)"),
    "surface": ("--surface", "kubelka-munk only: flat surface reflectance, in [0, 1] (default 0.02)"),
    "background": ("--background", "absorption of the dermis besides blood and water, cm⁻¹ (≥ 0)"),
    "vessel_min_um": ("--vessel-min-um", "smallest radius of the dermis' blood vessels, µm (> 0)"),
    "vessel_max_um": ("--vessel-max-um", "largest radius of the dermis' blood vessels, µm (≥ --vessel-min-um)"),
    "epidermis_scattering": ("--epidermis-scattering", "the epidermis' reduced scattering over the dermis' (> 0)"),
    "melanin_power": ("--melanin-power",
                      "power p of the melanosome's absorption 67.9 (λ/500 nm)^-p mm⁻¹, in [0, 10] (its log slope "
                      "at 500 nm, which --melanin-law exponential keeps)"),
}
"""SkinParameters field → (flag, help)."""
HELD_IN_FIT = ("epidermis_mm", "n", "background", "vessel_min_um", "vessel_max_um", "epidermis_scattering",
               "melanin_power")
"""Parameters a fit holds at what the flags say (the others it fits)."""
SPECTRA_MAX = 1000
"""``--max-spectra`` unless given."""
METHOD_MEANINGS = {
    "adding-doubling": "two layers under a Fresnel boundary, radiative transport (default)",
    "kubelka-munk": "the same layers by two-flux Kubelka–Munk, a flat surface term, no boundary",
}


def add_parsers(commands) -> None:
    """Add the parser of skin."""
    from ..datasets.skin_model import SkinParameters

    defaults = SkinParameters()
    p = commands.add_parser("skin", run=command_skin,
                            help="the skin model's reflectance and layers, or its fit to measured spectra")
    for name, (option, text) in PARAMETER_FLAGS.items():
        default = getattr(defaults, name)
        p.add_argument(option, dest=name, metavar="X",
                       help=text + (f" (default {default:g})" if default is not None else ""))
    p.add_argument("--melanin-law", metavar="LAW",
                   help="the melanosome's spectral law, --melanin-power p being its logarithmic slope at 500 nm: "
                        "power (default): 67.9 (λ/500 nm)^-p mm⁻¹; exponential: 67.9 exp(-p (λ - 500 nm)/500 nm) "
                        "mm⁻¹, in vivo melanin's form (Zonios et al. 2008), calibrated with --melanin-power 4.2 "
                        "--background 0.13 (through a 5 mm port: 4.0 and 0); held with --fit")
    p.add_argument("--method", default="adding-doubling",
                   help="reflectance method: " + "; ".join(f"{k}: {v}" for k, v in METHOD_MEANINGS.items()))
    p.add_argument("--grid", default="400:700:1", help="wavelengths START:END:STEP in nm (default 400:700:1)")
    p.add_argument("--plot", help="write R(λ) beside the measured skin spectra's range (--compare) to this PNG")
    p.add_argument("--compare", default=None,
                   help="with --plot: comma-separated measured skin sets (names or CSV paths) drawn as ranges "
                        "(default skin, the 30 Vrhel skins; e.g. skin,../shared/data/skin_nist.csv)")
    p.add_argument("--fit", metavar="FILE.csv",
                   help="fit every column of a reflectance table (CSV: wavelength nm, one column per sample; or a "
                        "reflectance set name such as skin) over its own wavelengths in --fit-range")
    p.add_argument("--fit-range", default=None, metavar="START:END",
                   help="with --fit: the wavelengths fitted, nm (default 400:700); a range wider than the table's "
                        "fits the table's wavelengths within it, and says so")
    p.add_argument("--port-mm", metavar="D",
                   help="the contact instrument's sample port (the spot measured) diameter, mm (> 0): the model is "
                        "read as through it, the light that leaves the skin outside it lost (lateral loss, "
                        "Farrell et al. 1992's diffusion, a beam at the port's centre); with --fit the fitted "
                        "parameters are then the skin's, the loss the instrument's (the NIST skins: 5, with "
                        "--background 0: the default background stands in part for this loss). Default: none, an "
                        "area much larger than the light's spread, as a camera sees skin")
    p.add_argument("--workers", help="with --fit: processes (default: every core)")
    p.add_argument("--max-spectra", default=str(SPECTRA_MAX),
                   help=f"with --fit: refuse tables of more spectra than this (default {SPECTRA_MAX}; the estimate "
                        "is printed with the refusal)")
    p.add_argument("--quiet", action="store_true", help="with --fit: no progress bar on stderr")
    add_common(p)


def parameters_of(args: argparse.Namespace, names=tuple(PARAMETER_FLAGS)):
    """The :class:`SkinParameters` of the flags (the others at their defaults), each checked naming its flag."""
    from dataclasses import replace

    from ..datasets.skin_model import SkinParameters, check_parameters

    values = {}
    for name in names:
        text = getattr(args, name)
        if text is None:
            continue
        option = PARAMETER_FLAGS[name][0]
        try:
            values[name] = float(text)
        except ValueError:
            raise SkinrenderError(f"{option} must be a number, got {text!r}", flag=option) from None
        one = replace(SkinParameters(), **{name: values[name]})
        flag(option, check_parameters, one)
    if args.melanin_law is not None:  # a name, not a number
        values["melanin_law"] = args.melanin_law
        flag("--melanin-law", check_parameters, replace(SkinParameters(), melanin_law=args.melanin_law))
    parameters = SkinParameters(**values)
    flag("--vessel-min-um", check_parameters, parameters)  # the one check across flags: min ≤ max
    return parameters


def _port(args: argparse.Namespace) -> float | None:
    """``--port-mm``: a diameter in mm > 0, or ``None`` (:func:`~skinrender.datasets.port_loss.check_port`, its
    refusal worded with the flag)."""
    from ..datasets.port_loss import check_port
    from .common import flagged

    return flagged({"port_mm": "--port-mm"}, check_port, args.port_mm)


def _method(args: argparse.Namespace) -> str:
    from ..datasets.skin_model import SKIN_REFLECTANCE_METHODS
    from ..methods import validate_method

    return flag("--method", validate_method, args.method, SKIN_REFLECTANCE_METHODS, "method")


def command_skin(args: argparse.Namespace) -> None:
    if args.fit is not None:
        return _command_fit(args)
    for option, default in (("fit_range", None), ("workers", None), ("max_spectra", str(SPECTRA_MAX)),
                            ("quiet", False)):  # --quiet silences the fit's progress: nothing else has one
        if getattr(args, option) != default:
            raise SkinrenderError(f"--{option.replace('_', '-')} goes with --fit", flag=f"--{option.replace('_', '-')}")
    from ..datasets.skin_fit import measured_reflectance
    from ..datasets.skin_model import skin_layers

    method = _method(args)
    port_mm = _port(args)
    check_output(args.plot, "--plot", (".png",))
    if args.plot is None and args.compare is not None:  # given at all: even its default's value is a request
        raise SkinrenderError("--compare names the measured sets drawn with --plot: give --plot FILE.png",
                              flag="--compare")
    compare = _compare_sets(args) if args.plot else []
    parameters = parameters_of(args)
    from ..datasets.skin_fit import FIT_MODELS
    from ..methods import takes

    if parameters.surface is not None and not takes(FIT_MODELS[method], "surface"):
        raise SkinrenderError("--surface is the kubelka-munk method's flat surface reflectance; adding-doubling's "
                              "surface is its Fresnel boundary (--n)", flag="--surface")
    if args.n is not None and takes(FIT_MODELS[method], "surface"):  # a flat surface: no boundary refracts
        raise SkinrenderError("--n is the refractive index of adding-doubling's Fresnel boundary; kubelka-munk has "
                              "none (its surface is --surface's flat reflectance)", flag="--n")
    from .common import grid_of

    grid = grid_of(args)
    lam = grid.wavelengths
    layers = flag("--grid", skin_layers, lam, parameters)
    with np.errstate(all="ignore"):
        reflectance = flag("--grid", measured_reflectance, lam, parameters, method, port_mm)
    if not np.all(np.isfinite(reflectance)):
        raise SkinrenderError(f"the parameters give no finite reflectance ({method})")
    document = {"method": method, "parameters": _parameters_dict(parameters), "port_mm": port_mm,
                "wavelength_nm": lam.tolist(), "reflectance": reflectance.tolist(),
                "layers": [layer.as_dict() for layer in layers]}
    if args.plot:
        from ..studies.figures import figure_skin_model

        write_output(args.plot, lambda stream: figure_skin_model(  # whole or not at all, its failure naming --plot
            lam, reflectance, f"skin model ({method}), melanin {parameters.melanin:g}, blood {parameters.blood:g}"
            + ("" if parameters.melanin_law == "power" else f", melanin law {parameters.melanin_law}")
            + ("" if port_mm is None else f", through a {port_mm:g} mm port"),
            compare, stream), "--plot")
        document["plot"] = args.plot
    emit(args, document, _text(method, parameters, lam, reflectance, layers, args.plot, port_mm))


def _compare_sets(args: argparse.Namespace) -> list[tuple]:
    """The measured sets of ``--compare``: ``(name, wavelengths nm, values)`` each, checked before any work."""
    from ..datasets import reflectances

    items = [item.strip() for item in str("skin" if args.compare is None else args.compare).split(",")]
    if not all(items):
        raise SkinrenderError(f"--compare: expected comma-separated reflectance sets, got {args.compare!r}",
                              flag="--compare")
    sets = [flag("--compare", reflectances, item) for item in items]
    return [(s.name, s.wavelengths, s.values) for s in sets]


def _parameters_dict(parameters) -> dict:
    from dataclasses import asdict

    return asdict(parameters)


def _text(method, parameters, lam, reflectance, layers, plot, port_mm) -> str:
    step = max(1, int(math.ceil(lam.size / 13)))
    rows = [[f"{lam[i]:g}", f"{reflectance[i]:.4f}", f"{layers[0].mu_a_per_mm[i]:.4g}",
             f"{layers[1].mu_a_per_mm[i]:.4g}", f"{layers[1].mu_s_per_mm[i]:.4g}"] for i in range(0, lam.size, step)]
    described = ", ".join(f"{k} {v:g}" if not isinstance(v, str) else f"{k} {v}"
                          for k, v in _parameters_dict(parameters).items() if v is not None)
    lines = [f"skin model ({method}): {described}",
             f"layers: epidermis {layers[0].thickness_mm:g} mm over a semi-infinite dermis, g {layers[0].g:g}, "
             f"n {layers[0].n:g}",
             table(rows, ["nm", "R" if port_mm is None else f"R through a {port_mm:g} mm port",
                          "epidermis μa /mm", "dermis μa /mm", "μs /mm"])]
    if plot:
        lines.append(f"plot: {plot}")
    return "\n".join(lines)


def _command_fit(args: argparse.Namespace) -> None:
    from ..datasets import reflectances
    from ..datasets.skin_fit import FIT_BOUNDS, FIT_PARAMETERS, fit_seconds, fit_skin_spectra
    from ..execution import check_workers

    for name, (option, _) in PARAMETER_FLAGS.items():
        if name not in HELD_IN_FIT and getattr(args, name) is not None:
            raise SkinrenderError(f"{option} is fitted with --fit; only "
                                  f"{', '.join(PARAMETER_FLAGS[k][0] for k in HELD_IN_FIT)} are held", flag=option)
    if args.plot is not None or args.compare is not None:
        raise SkinrenderError("--plot and --compare draw the forward model; they do not go with --fit", flag="--plot")
    if args.grid != "400:700:1":
        raise SkinrenderError("--grid sets the forward model's wavelengths; --fit uses the table's own "
                              "wavelengths in --fit-range", flag="--grid")
    method = _method(args)
    from ..datasets.skin_fit import FIT_MODELS
    from ..methods import takes

    if args.n is not None and takes(FIT_MODELS[method], "surface"):  # held, it would change nothing: no boundary
        raise SkinrenderError("--n is the refractive index of adding-doubling's Fresnel boundary; kubelka-munk has "
                              "none", flag="--n")
    held = parameters_of(args, HELD_IN_FIT)
    port_mm = _port(args)
    start, end = _fit_range("400:700" if args.fit_range is None else args.fit_range)
    workers = check_workers(None if args.workers is None else integer_in(args.workers, "--workers", 1), "--workers")
    limit = integer_in(args.max_spectra, "--max-spectra", 1)
    measured = flag("--fit", reflectances, args.fit)
    keep = (measured.wavelengths >= start) & (measured.wavelengths <= end)
    lam = measured.wavelengths[keep]
    if lam.size < 8:
        raise SkinrenderError(f"--fit: {measured.name} has {lam.size} wavelengths in --fit-range "
                              f"{start:g}–{end:g} nm; "
                              "a fit needs at least 8", flag="--fit")
    if measured.count > limit:
        seconds = fit_seconds(measured.count, lam.size, method, workers)
        raise SkinrenderError(f"--fit: {measured.count} spectra is more than --max-spectra {limit} (about "
                              f"{seconds / 60:.2g} min on {workers} cores at the measured "
                              f"~{fit_seconds(1, lam.size, method):.2g} s per spectrum); raise the limit or fit fewer",
                              flag="--fit")
    fits = flag("--fit", fit_skin_spectra, lam, measured.values[:, keep], measured.names, method, workers,
                None if args.quiet else sys.stderr, held, port_mm=port_mm)
    rms = np.array([f.rms for f in fits if f.converged])
    summary = ({"median": float(np.median(rms)), "p95": float(np.percentile(rms, 95)), "max": float(rms.max())}
               if rms.size else None)
    skins = sum(not f.not_skin for f in fits)
    document = {"method": method, "source": measured.name, "wavelength_nm": lam.tolist(),
                "bounds": {k: list(FIT_BOUNDS[k][:2]) + [FIT_BOUNDS[k][2]] for k in FIT_PARAMETERS[method]},
                "held": {k: getattr(held, k) for k in (*HELD_IN_FIT, "melanin_law")}, "port_mm": port_mm,
                "fits": [f.as_dict(method) for f in fits], "converged": int(sum(f.converged for f in fits)),
                "skin": int(skins), "rms": summary, "fit_range_nm": [start, end], "notes": []}
    if start < measured.wavelengths[0] or end > measured.wavelengths[-1]:  # said, not clipped silently
        document["notes"].append(f"--fit-range {start:g}–{end:g} nm is wider than {measured.name}'s "
                                 f"{measured.wavelengths[0]:g}–{measured.wavelengths[-1]:g} nm: fitted over "
                                 f"{lam[0]:g}–{lam[-1]:g} nm")
    rows = [[f.name[:32], f"{f.rms:.4f}" if math.isfinite(f.rms) else "—",
             *(f"{getattr(f.parameters, k):.4g}" for k in FIT_PARAMETERS[method]),
             ", ".join(f"{k} {v}" for k, v in f.bounds_hit.items()) or "-", "yes" if f.converged else "NO",
             "NO" if f.not_skin else "yes"]
            for f in fits]
    refused = [f"not skin: {f.name}: {f.not_skin_reason}" for f in fits if f.not_skin]
    text = (f"{method} fit of {measured.count} spectra from {measured.name}, {lam.size} wavelengths "
            f"{lam[0]:g}–{lam[-1]:g} nm" + ("" if port_mm is None else f", read through a {port_mm:g} mm port")
            + f"; held: melanin law {held.melanin_law}, melanin power {held.melanin_power:g}, "
              f"background {held.background:g} cm⁻¹"
            + "\n"
            + table(rows, ["spectrum", "RMS", *FIT_PARAMETERS[method], "on a bound", "converged", "skin"]) + "\n"
            + "".join(line + "\n" for line in refused + [f"note: {n}" for n in document["notes"]])
            + (f"RMS median {summary['median']:.4f}, 95th percentile {summary['p95']:.4f}, max {summary['max']:.4f}; "
               if summary else "")
            + f"{document['converged']} of {len(fits)} converged; "
            + f"{sum(1 for f in fits if f.bounds_hit)} sit on a bound; {skins} of {len(fits)} are skin")
    emit(args, document, text)
    if not skins:
        raise SystemExit(1)


def _fit_range(text: str) -> tuple[float, float]:
    parts = str(text).replace("nm", "").split(":")
    try:
        start, end = (float(part) for part in parts)
    except ValueError:
        raise SkinrenderError(f"--fit-range must be START:END in nm (e.g. 400:700), got {text!r}",
                              flag="--fit-range") from None
    if not (math.isfinite(start) and math.isfinite(end) and 0 < start < end):
        raise SkinrenderError(f"--fit-range must be finite nm with 0 < START < END, got {text!r}", flag="--fit-range")
    return start, end
