"""
The face sweep: ``face-sweep`` renders the face for every camera × light
pair × skin × level of physics, on every core or a Dask cluster, and scores
skin detection on each render as ``ladder`` does
(:mod:`skinrender.studies.face.sweep`).

``--camera`` and ``--skin`` repeat (camera and skin specs hold commas);
``--lights`` takes comma-separated ``PREVAILING/CALIBRATION`` pairs and
``--levels`` comma-separated levels.

Units: temperatures K, times s, image sides pixels, NCC and rates fractions.
"""

from __future__ import annotations

import argparse
import sys

from ..errors import SkinrenderError
from ..workload import MINUTES_MAX
from .common import (HELP_CAMERA, SEED_MAX, SPP_MAX, add_common, add_max_minutes, check_output, emit, flag,
                     integer_in, interruptible, positive_number, table, variant_of)
from .detection_options import add_detection_options, detection_tolerance_from, skin_set_from
from .preflight import check_dask
from .face import HELP_SKIN, SIZE_MAX, level_names, levels_of, noise_sensor, planckian_flag
from .face_inputs import refuse_repeated, skins_from

__all__ = ["add_parsers", "command_face_sweep", "light_pairs", "LIGHTS_DEFAULT", "SIZE_DEFAULT", "SPP_DEFAULT"]

LIGHTS_DEFAULT = "2300/5900,2856/5900,5900/5900,10000/5900"
"""``--lights`` unless given: horizon sunlight to blue sky, balanced to daylight (as the face loci)."""

SIZE_DEFAULT = 64
"""``--size`` unless given, pixels."""

SPP_DEFAULT = 32
"""``--spp`` unless given."""


def add_parsers(commands) -> None:
    """Add the parser of face-sweep."""
    from ..studies.face.locus import SKIN_TONES
    from ..studies.face.sweep import RENDERS_MAX, SWEEP_SAMPLES_MAX
    from ..studies.face.ladder import LEVELS_DEFAULT

    p = commands.add_parser("face-sweep", run=command_face_sweep,
                            help="the face rendered for every camera × light pair × skin × level of "
                            "physics, on every core or a Dask cluster, with the skin's NCC and the skin locus's "
                            "detection rates for each")
    p.add_argument("--camera", action="append", required=True,
                   help="a camera (repeat the flag for several); " + HELP_CAMERA)
    p.add_argument("--lights", action="append", metavar="P/C[,P/C…]",
                   help="comma-separated PREVAILING/CALIBRATION pairs of Planckian lights (kelvin, A or H), e.g. "
                   f"2856/5900,2300/5900; the flag may repeat (default {LIGHTS_DEFAULT})")
    p.add_argument("--skin", action="append",
                   help="a skin (repeat the flag for several): " + HELP_SKIN.split(" (default")[0]
                   + "; default: light to very dark, " + " ".join(SKIN_TONES))
    p.add_argument("--levels", default=",".join(LEVELS_DEFAULT),
                   help=f"comma-separated levels of physics ({level_names()}; effects combine with '+'); default "
                   + ",".join(LEVELS_DEFAULT))
    p.add_argument("--scene", default="face", help="face scene: a bundled name (face) or a .toml path")
    p.add_argument("--size", metavar="PX", default=str(SIZE_DEFAULT),
                   help=f"image side in pixels (default {SIZE_DEFAULT})")
    p.add_argument("--spp", metavar="N", default=str(SPP_DEFAULT), help=f"samples per pixel (default {SPP_DEFAULT})")
    p.add_argument("--seed", metavar="S", default="0", help="sampler seed, every render the same (default 0)")
    p.add_argument("--imager", help="image sensor of the noise level: a preset or a TOML (default sony-icx418)")
    p.add_argument("--illuminance", metavar="LUX",
                   help="the key light's illuminance at the face, lx (default: the scene's); only noise sees it")
    p.add_argument("--variant", help="force a Mitsuba variant (llvm_ad_spectral, cuda_ad_spectral, "
                   "scalar_spectral); default: the fastest that works here, the same in every worker")
    p.add_argument("--workers", metavar="N", help="processes (default: every core); 1 renders in this process")
    p.add_argument("--dask", metavar="ADDRESS", help="run on a Dask cluster (scheduler address, tcp://host:8786)")
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    p.add_argument("--csv", help="write every combination's row to this CSV file (whole or not at all)")
    p.add_argument("--max-renders", metavar="N", default=str(RENDERS_MAX),
                   help=f"refuse sweeps of more renders than this (default {RENDERS_MAX})")
    from .bands_flags import add_cameras_arguments

    add_cameras_arguments(p)
    p.add_argument("--max-samples", metavar="N", default=f"{SWEEP_SAMPLES_MAX:g}",
                   help=f"refuse sweeps of more samples (renders × pixels × spp) than this (default "
                   f"{SWEEP_SAMPLES_MAX:g})")
    add_max_minutes(p, "the renders × --size² × --spp at each level's rate")
    add_detection_options(p)
    add_common(p)


def light_pairs(values: list[str]) -> list[tuple[float, float]]:
    """The (prevailing, calibration) pairs of every ``--lights``, K."""
    pairs = []
    for value in values:
        for item in str(value).split(","):
            if not item.strip():
                raise SkinrenderError(f"--lights: comma-separated PREVAILING/CALIBRATION pairs, none empty, got "
                                      f"{value!r}", flag="--lights")
            parts = item.split("/")
            if len(parts) != 2 or not all(part.strip() for part in parts):
                raise SkinrenderError(f"--lights: expected PREVAILING/CALIBRATION pairs such as 2856/5900, got "
                                      f"{item.strip()!r}", flag="--lights")
            pairs.append((planckian_flag(parts[0].strip(), "--lights"), planckian_flag(parts[1].strip(), "--lights")))
    if not pairs:
        raise SkinrenderError("--lights: name at least one PREVAILING/CALIBRATION pair", flag="--lights")
    refuse_repeated("--lights", [f"{p:g}/{c:g} K" for p, c in pairs])
    return pairs


def _checked(args: argparse.Namespace) -> dict:
    """Every flag checked, before any render: the arguments of :func:`~skinrender.studies.face.sweep.face_sweep`."""
    import numpy as np

    from ..model.response import response
    from ..rendering.face.scene import load_face_scene
    from ..spectra import GRID_DEFAULT
    from ..studies.face.locus import SKIN_TONES
    from ..execution import WORKERS_MAX

    check_output(args.csv, "--csv", (".csv",))
    from .bands_flags import cameras_of

    cams = cameras_of(args.camera)
    pairs = light_pairs(args.lights or [LIGHTS_DEFAULT])
    for cam in cams:
        for t in sorted({t for pair in pairs for t in pair}):
            flag({"camera": "--camera", None: "--lights"}, response, cam, np.ones((1, GRID_DEFAULT.size)), t, t)
    skins = skins_from(args.skin or SKIN_TONES)
    levels = levels_of(args.levels)
    flag("--scene", load_face_scene, args.scene)
    variant_of(args.variant)
    imager, lux = noise_sensor(args, levels)  # (the imager loaded once, the lux checked)
    max_samples = positive_number(args.max_samples, "--max-samples", "renders × pixels × spp")
    from .bands_flags import bands_for

    bands = bands_for(args, cams)
    check_dask(args)  # an empty address, another server or none there: refused before any render
    return {
        "spectral": bands is not None, **({"bands": bands} if bands is not None else {}),
        "cameras": cams, "lights": pairs, "skins": skins, "levels": levels, "scene": args.scene,
        "size": integer_in(args.size, "--size", 1, SIZE_MAX), "spp": integer_in(args.spp, "--spp", 1, SPP_MAX),
        "seed": integer_in(args.seed, "--seed", 0, SEED_MAX), "variant": args.variant, "imager": imager,
        "illuminance": lux,
        "workers": None if args.workers is None else integer_in(args.workers, "--workers", 1, WORKERS_MAX),
        "dask": args.dask, "max_renders": integer_in(args.max_renders, "--max-renders", 1, 10**9),
        "max_samples": max_samples, "detection_tolerance": detection_tolerance_from(args.detection_tolerance),
        "max_minutes": MINUTES_MAX if args.max_minutes is None else positive_number(args.max_minutes, "--max-minutes",
                                                                                   "minutes"),
        "skin_set": _skin_set(args.skin_set, cams, pairs),
    }


def _skin_set(spec: str | None, cams, pairs):
    """``--skin-set`` (``spec``) checked for every camera at every calibration (K, ``pairs``' second)."""
    skins = None
    for cam in cams:
        skins = skin_set_from(spec, cam, [c for _, c in pairs])
    return skins


def command_face_sweep(args: argparse.Namespace) -> None:
    """The sweep; rendering in this process (``--workers 1``), in a thread Ctrl-C can stop at once (a pool's
    workers are stopped by the sweep itself, which Ctrl-C reaches between renders)."""
    if args.dask is None and str(args.workers).strip() == "1":
        return interruptible(_face_sweep)(args)
    return _face_sweep(args)


def _face_sweep(args: argparse.Namespace) -> None:
    from ..studies.face.sweep import face_sweep

    result = face_sweep(**_checked(args), progress=None if args.quiet else sys.stderr)
    if args.csv is not None:
        result.to_csv(args.csv, "--csv")
    document = {**result.document(), "csv": args.csv}
    used = sorted({row["spp"] for row in document["combinations"]})  # the sampler may round spp up
    document["spp_requested"] = result.spp
    if len(used) == 1:
        document["spp"] = used[0]
    from ..rendering.variants import ROUNDED

    if not ROUNDED:  # rendered in worker processes, whose warnings are not seen here: said once by the command line
        ROUNDED.extend(row["spp"] for row in document["combinations"] if row["spp"] != result.spp)

    def triple(values) -> str:
        return "—" if values is None else " ".join(f"{v:.4f}" for v in values)

    def rate(value) -> str:
        return "—" if value is None else f"{value:.3f}"

    rows = [[row["camera"], f"{row['prevailing_K']:g}/{row['calibration_K']:g}", row["skin"], row["level"],
             f"{row['seconds']:.2f}", row["spp"], triple(row["skin_ncc_mean"]), rate(row["tpr"]), rate(row["fpr"]),
             f"{rate(row['detection']['tpr'])} ({rate(row['detection']['tpr_eq4'])})",
             f"{rate(row['detection']['fpr'])} ({rate(row['detection']['fpr_eq4'])})", row["detection"]["verdict"]]
            for row in document["combinations"]]
    spectral = result.spectral
    how = ("" if spectral is None else f" seen through {spectral['renders']} × 12 spectral render"
           f"{'s' * (spectral['renders'] != 1)} of {spectral['bands']} bands ({spectral['bands_nm']} nm)")
    text = (table(rows, ["camera", "P/C K", "skin", "level", "s", "spp", "skin NCC r g b", "TPR seen", "FPR seen",
                         "TPR (Eq. 4)", "FPR (Eq. 4)", "detection"])
            + f"\n(the {document['combinations'][0]['skin_set']} skin locus; seen: as rendered; TPR, FPR: the "
            "renderer's noise separated, Eq. 4's in brackets; detection: the changes held to "
            f"±{args.detection_tolerance})"
            + f"\n{len(rows)} {'render' if spectral is None else 'combination'}{'s' * (len(rows) != 1)}{how} of "
            f"{result.size}×{result.size} px at "
            f"{document['spp']} spp in "
            f"{result.elapsed_s:.1f} s ({'Dask' if result.dask else f'{result.workers} worker' + 's' * (result.workers > 1)}, {result.variant})"
            + (f"; wrote {args.csv}" if args.csv else ""))
    emit(args, document, text)
