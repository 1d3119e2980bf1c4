"""
The image sensor: ``imagers`` (the presets) and ``score`` (the criteria for one
camera, with the noise-aware detection rates through an imager).

Units: pixel pitch µm, charge e⁻, system gain DN/e⁻, illuminance lx, exposure
s, temperatures K; rates are fractions in [0, 1].
"""

from __future__ import annotations

import argparse
import math
import sys

from ..errors import SkinrenderError
from ..files import write_output
from .common import (EXPOSURE_MAX, HELP_CAMERA, add_common, add_max_minutes, camera_of, check_output, check_seed, emit, flag, integer_in,
                     positive_number, table)
from .preflight import check_lights

__all__ = [
    "SAMPLES_DEFAULT",
    "SEED_LIMIT",
    "add_parsers",
    "command_imagers",
    "command_score",
]

SAMPLES_DEFAULT = 16
"""``score --samples``: noisy pixels per (reflectance, prevailing, calibration)."""

SEED_LIMIT = 2**32
"""``score --seed`` lies in [0, 2³²): numpy's seed range as a 32-bit integer."""


def add_parsers(commands) -> None:
    """Add the parsers of imagers, score, ptc."""
    p = commands.add_parser("ptc", run=command_ptc,
                            help="EMVA 1288-style photon transfer of the simulated camera, measured from "
                            "rendered pixels: gain DN/e⁻, read noise e⁻, full well e⁻, linearity, SNR; the fits "
                            "tested against the imager's stated figures (z = (fit − stated)/SE, Šidák, α 0.01): "
                            "exit 0 pass, 1 fail")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--imager", required=True, help="image sensor: a preset (see 'skinrender imagers') or a TOML file")
    p.add_argument("--temperature", type=float, default=5900.0, help="the light's Planckian temperature, K (default 5900)")
    p.add_argument("--illuminance", type=float, default=500.0, help="illuminance at the grey chart, lx (default 500)")
    p.add_argument("--points", type=int, default=24, help="exposures from 0 past saturation (default 24)")
    p.add_argument("--spp", type=int, default=64, help="samples per pixel of the one render (default 64)")
    p.add_argument("--seed", type=int, default=0, help="render and sensor seed (default 0)")
    p.add_argument("--plot", help="write the photon transfer curve to this PNG")
    add_common(p)

    p = commands.add_parser("imagers", run=command_imagers,
                            help="list the imager presets (pixel µm, full well e⁻, read noise e⁻, "
                            "gain DN/e⁻, ADC bits)")
    add_common(p)

    p = commands.add_parser("score", run=command_score,
                            help="the criteria for one camera: skin/Munsell gamut ratio, Munsell false "
                            "positives in the skin locus, and with --imager the rates on noisy pixels")
    p.add_argument("--camera", required=True, help=HELP_CAMERA)
    p.add_argument("--illuminants", default="paper",
                   help="illuminant set: 'paper' (the ten, default), 'auto' (Stage 1) or comma-separated kelvin")
    p.add_argument("--skin", default="skin", help="skin reflectance set, name or CSV path (default skin)")
    p.add_argument("--munsell", default="munsell", help="Munsell reflectance set, name or CSV path (default munsell)")
    p.add_argument("--imager", help="image sensor: a preset (see 'skinrender imagers') or a TOML file; adds the "
                   "detection rates on its noisy pixels (needs --illuminance)")
    p.add_argument("--illuminance", metavar="LUX", help="illuminance of the chart, lx > 0, under every illuminant")
    p.add_argument("--exposure", metavar="auto|SECONDS",
                   help="exposure: 'auto' (default: the white under the calibration light at 70 %% of the full "
                   "well) or seconds > 0")
    p.add_argument("--samples", metavar="N",
                   help=f"noisy pixels per reflectance and (prevailing, calibration) pair (default {SAMPLES_DEFAULT})")
    p.add_argument("--seed", metavar="S", help="random seed, an integer in [0, 2**32) (default 0)")
    add_max_minutes(p, "--samples × the reflectances × the illuminant pairs")
    add_common(p)


def command_imagers(args: argparse.Namespace) -> None:
    from ..model.imager import list_imagers

    imagers = list_imagers()
    rows = [[i["name"], f"{i['pixel_um']:g}", f"{i['full_well_e']:g}", f"{i['read_noise_e']:g}",
             f"{i['gain_dn_per_e']:g}", i["bits"], i["source"]] for i in imagers]
    text = table(rows, ["name", "pixel µm", "full well e⁻", "read noise e⁻", "gain DN/e⁻", "bits", "source"])
    emit(args, {"imagers": imagers}, text)


def _noise_options(args: argparse.Namespace) -> dict | None:
    """The checked imager flags, or ``None`` without ``--imager``; nothing heavy is done here."""
    given = [name for name in ("illuminance", "exposure", "samples", "seed", "max_minutes")
             if getattr(args, name) is not None]
    if args.imager is None:
        if given:
            option = f"--{given[0].replace('_', '-')}"
            raise SkinrenderError(f"{option} applies to the noisy rates: give --imager S too", flag=option)
        return None
    from ..model.imager import imager

    if args.illuminance is None:
        raise SkinrenderError("--imager needs --illuminance LUX (the chart's illuminance, lx > 0)", flag="--imager")
    exposure = args.exposure if args.exposure is not None else "auto"
    if exposure.strip().lower() == "auto":
        exposure = "auto"
    else:
        exposure = positive_number(exposure, "--exposure", "s, or 'auto'", EXPOSURE_MAX)
    return {
        "imager_": flag("--imager", imager, args.imager),
        "illuminance_lux": positive_number(args.illuminance, "--illuminance", "lx"),
        "exposure": exposure,
        "samples": SAMPLES_DEFAULT if args.samples is None else integer_in(args.samples, "--samples", 1),
        "seed": 0 if args.seed is None else integer_in(args.seed, "--seed", 0, SEED_LIMIT - 1),
    }


def _rate_text(rate: float | None, error: float | None) -> str:
    """A rate ± its standard error, or ``undefined``."""
    return "undefined" if rate is None else f"{rate:.4f} ± {error:.4f}"


def command_score(args: argparse.Namespace) -> None:
    from ..datasets import reflectances
    from ..evaluation.gamut import gamut_all_calibrations
    from ..evaluation.locus import false_positive_rate, skin_locus
    from ..evaluation.noisy_detection import SECONDS_PER_NOISY_PIXEL, noisy_detection
    from ..workload import check_work
    from ..model.stage1 import illuminant_set
    from ..spectra import GRID_DEFAULT

    noise = _noise_options(args)
    cam = camera_of(args)
    temperatures = flag({"camera": "--camera", None: "--illuminants"}, illuminant_set, args.illuminants, cam)
    skin, munsell = flag("--skin", reflectances, args.skin), flag("--munsell", reflectances, args.munsell)
    skin_gamut = gamut_all_calibrations(cam, skin, temperatures)
    munsell_gamut = gamut_all_calibrations(cam, munsell, temperatures)
    ratio = skin_gamut.volume / munsell_gamut.volume if munsell_gamut.volume > 0 else None
    locus = skin_locus(cam, skin, temperatures)
    fpr = false_positive_rate(locus, cam, munsell)
    document = {
        "camera": cam.name, "illuminants_K": temperatures.tolist(), "skin": skin.name, "munsell": munsell.name,
        "ratio_all": ratio, "skin_volume": skin_gamut.volume, "munsell_volume": munsell_gamut.volume, "fpr": fpr,
    }
    text = (f"{cam.name} over {len(temperatures)} illuminants (every calibration):\n"
            f"  gamut ratio {skin.name}/{munsell.name}: "
            + ("undefined (degenerate Munsell gamut)" if ratio is None else f"{ratio:.6g}") + "\n"
            f"  false positives ({munsell.name} in the {skin.name} locus, noise-free): {fpr:.4f}")
    if noise is not None:
        pixels = (skin.count + munsell.count) * len(temperatures) ** 2
        check_work(noise["samples"] * pixels * SECONDS_PER_NOISY_PIXEL, "--samples",
                   f"{noise['samples']} noisy samples of {pixels} reflectance-and-light pairs", args.max_minutes,
                   fewer="ask for fewer --samples")
        result = noisy_detection(cam, skin.on(GRID_DEFAULT), munsell.on(GRID_DEFAULT), temperatures, locus=locus,
                                 **noise)
        document["noisy"] = {
            "imager": result.imager, "illuminance_lux": result.illuminance_lux, "exposure_s": list(result.exposure_s),
            "calibrations_K": list(result.calibrations_K), "samples": result.samples, "seed": noise["seed"],
            "tpr": result.tpr, "fpr": result.fpr, "tpr_se": result.tpr_se, "fpr_se": result.fpr_se,
            "tpr_noise_free": result.tpr_noise_free, "fpr_noise_free": result.fpr_noise_free,
            "skin_ncc_std": [None if math.isnan(v) else v for v in result.skin_ncc_std],
            "undefined": result.undefined, "black_share": {"skin": result.black_share[0],
                                                            "nonskin": result.black_share[1]},
            "clipping": result.clipping, "notes": list(result.notes),
        }
        exposures = (f"{min(result.exposure_s) * 1e3:.4g}–{max(result.exposure_s) * 1e3:.4g} ms"
                     if noise["exposure"] == "auto" else f"{result.exposure_s[0] * 1e3:.4g} ms")
        text += (f"\nthrough {result.imager} at {result.illuminance_lux:g} lx, exposure {exposures} "
                 f"({result.samples} noisy pixels per sample and pair, seed {noise['seed']}):\n"
                 f"  skin detected (TPR): {_rate_text(result.tpr, result.tpr_se)} "
                 f"(noise-free {result.tpr_noise_free:.4f})\n"
                 f"  false positives (FPR): {_rate_text(result.fpr, result.fpr_se)} "
                 f"(noise-free {result.fpr_noise_free:.4f})"
                 + "".join(f"\n  note: {note}" for note in result.notes)
                 + "".join(f"\n  {key} undefined: {why}" for key, why in result.undefined.items()))
    emit(args, document, text)


PTC_FIGURES = ("gain_dn_per_e", "read_noise_e", "dark_current_e_per_s", "full_well_e", "linearity_error")
"""The per-channel figures of ``ptc``, in the text's columns: every one its JSON has."""


def command_ptc(args: argparse.Namespace) -> None:
    from ..model.illuminant import illuminant
    from ..model.imager import imager
    from ..studies.figures import figure_ptc
    from ..rendering.settings import RenderSettings
    from ..studies.benchmarks.ptc import photon_transfer

    plot = check_output(args.plot, "--plot", (".png",))
    cam = camera_of(args)
    sensor = flag("--imager", imager, args.imager)
    positive_number(args.illuminance, "--illuminance", "lx")
    for name, value in (("--temperature", args.temperature),):
        if not (math.isfinite(value) and value > 0):
            raise SkinrenderError(f"{name} must be a finite number > 0, got {value}", flag=name)
    flag("--temperature", illuminant, args.temperature)
    check_lights(args, cam, [args.temperature], None, "--temperature")  # a light the camera sees at all
    if not 1 <= args.spp <= 65536:
        raise SkinrenderError(f"--spp must be an integer in [1, 65536], got {args.spp}", flag="--spp")
    check_seed(args.seed)
    integer_in(args.points, "--points", 4, 1000)  # before the progress line, so a refusal is its one line
    print(f"rendering the grey chart at {args.spp} spp …", file=sys.stderr)
    result = flag("--points", photon_transfer, cam, sensor, args.temperature, args.illuminance, args.points,
                  RenderSettings(spp=args.spp, seed=args.seed))
    if args.plot:
        write_output(plot, lambda stream: figure_ptc(result, stream), "--plot")
        result["plot"] = str(plot)
    text = _ptc_text(result, cam.name, sensor.name, args.illuminance)
    emit(args, result, text)
    if result["exit_status"]:
        raise SystemExit(result["exit_status"])


PTC_TESTED_LABELS = {"gain_dn_per_e": "gain DN/e⁻", "read_noise_e": "read noise e⁻",
                     "dark_current_e_per_s": "dark current e⁻/s"}
"""The tested figures' labels in ``ptc``'s text."""


def _ptc_text(result: dict, camera_name: str, sensor_name: str, lux: float) -> str:
    """``ptc``'s text: the figures per channel, then per tested figure and channel the fit, stated value, standard
    error and z, the test in words, what is information only, and the verdict with its exit status."""
    shown = lambda v, f=".4g": "undefined" if v is None else format(v, f)  # noqa: E731
    rows = [[name, *(shown(result[key][k]) for key in PTC_FIGURES)] for k, name in enumerate("RGB")]
    rows.append(["stated", *(f"{result['stated'][key]:.4g}" if key in result["stated"] else "" for key in PTC_FIGURES)])
    tests = [[label, channel, shown(result[key][k]), f"{result['stated'][key]:.4g}",
              shown(result["standard_error"][key][k], ".3g"),
              "not tested" if result["z"][key][k] is None else f"{result['z'][key][k]:+.2f}"]
             for key, label in PTC_TESTED_LABELS.items() for k, channel in enumerate("RGB")]
    check = result["checks"]["fits"]
    verdict = result["verdict"]
    return (f"photon transfer of {camera_name} through {sensor_name} ({len(result['points'])} exposures, "
            f"{lux:g} lx):\n"
            + table(rows, ["channel", "gain DN/e⁻", "read noise e⁻", "dark current e⁻/s", "full well e⁻",
                           "linearity %"])
            + "".join(f"\n{key} undefined: {why}" for key, why in result["undefined"].items())
            + "\n\nthe fits against the stated figures (z = (fit − stated) / SE):\n"
            + table(tests, ["figure", "channel", "fit", "stated", "SE", "z"])
            + f"\ntest: {check['test']}, α {check['alpha']:g}"
            + "".join(f"\ninformation only, {key}: {why}" for key, why in result["information_only"].items())
            + f"\nverdict: {verdict.upper().replace('_', ' ')} (exit status {result['exit_status']}): {check['reason']}"
            + ("" if check["statistic"] is None else
               f"; largest |z| {check['statistic']:.3g} ({check['worst_figure']}) against {check['threshold']:.3g}"))
