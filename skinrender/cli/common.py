"""
Command-line helpers
====================

What every command shares: the help texts, the argument groups (grid, model, search, render options), printing one
JSON document or a text table, and the grid and render options parsed from the arguments. Choices come from the
method tables of the package (:mod:`skinrender.methods`).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from ..errors import SkinrenderError, naming
from ..files import check_output_path, shown, write_stdout

__all__ = [
    "Parser", "flag", "flagged", "imaging_options", "camera_of", "check_output", "check_seed", "SEED_MAX",
    "HELP_CAMERA", "HELP_ILLUMINANT", "HELP_PLANCKIAN", "HELP_GRID", "add_common", "add_grid", "add_model", "add_search",
    "add_render", "emit", "table", "range_text", "grid_of", "grid_from", "settings_of", "settings_from",
    "camera_from", "choices_help", "coverage_hint", "interruptible", "add_max_minutes",
]

HELP_CAMERA = (
    "camera: 'gbell:N@P1,P2,P3' (sensor N, FWHM N·10 nm, peaks in nm), 'gbell:N,b=B@…', "
    "'impulse@P1,P2,P3', a bundled name (see 'skinrender cameras') or a CSV path "
    "(wavelength nm, R, G, B)"
)
HELP_ILLUMINANT = "kelvin (3300 or 3300K, a Planckian radiator), A (2856 K), H (Horizon, 2300 K) or a CSV path"
HELP_PLANCKIAN = ("kelvin (3300 or 3300K, a Planckian radiator), A (2856 K) or H (Horizon, 2300 K); no CSV: renders "
                  "need a temperature")
HELP_GRID = "integration grid START:END:STEP in nm (default 400:700:1)"


def choices_help(methods: dict) -> str:
    """``name: meaning; …`` of a method table (each method's :func:`~skinrender.methods.describe`), for a flag's
    help."""
    from ..methods import describe

    return "; ".join(f"{name}: {describe(method)}" for name, method in methods.items()).replace("%", "%%")


def add_common(parser: argparse.ArgumentParser) -> None:
    """``--json``."""
    parser.add_argument("--json", action="store_true", help="print one JSON document on stdout")


class Once(argparse.Action):
    """
    A value flag that may be given once, under any of its spellings (``--normalization`` and
    ``--normalisation``): a second one is refused, rather than the last silently winning.
    """

    def __call__(self, parser, namespace, values, option_string=None):  # noqa: D102 - argparse's hook
        seen = vars(namespace).setdefault("_given", {})
        if self.dest in seen:
            parser.error(f"{option_string}: {seen[self.dest]} was given already; give it once")
        seen[self.dest] = option_string
        setattr(namespace, self.dest, values)


def add_grid(parser: argparse.ArgumentParser, named_sets: bool = False) -> None:
    """``--grid`` and ``--extrapolation`` (``named_sets``: for bundled sets too, ``args.extrapolates_named``)."""
    from ..spectra import EXTRAPOLATIONS

    parser.add_argument("--grid", default="400:700:1", help=HELP_GRID)
    which = "reflectance sets (bundled ones too) and CSV cameras" if named_sets else "CSV cameras and reflectances"
    parser.add_argument("--extrapolation", default="refuse", choices=list(EXTRAPOLATIONS),
                        help=f"for {which} that do not cover the grid: " + choices_help(EXTRAPOLATIONS))
    parser.set_defaults(extrapolates_named=named_sets)


def add_model(parser: argparse.ArgumentParser) -> None:
    """``--normalization`` (``--normalisation`` accepted too) and ``--knee``."""
    from ..model.response import NORMALISATIONS

    parser.add_argument("--normalization", "--normalisation", dest="normalization", default="white",
                        action=Once, choices=list(NORMALISATIONS), help="illuminant normalisation: " + choices_help(NORMALISATIONS))
    parser.add_argument("--knee", action="store_true", help="apply the knee of Eq. 11 (output ≤ 255)")


def add_search(parser: argparse.ArgumentParser) -> None:
    """The reflectance sets and the executors of the Stage 3 search."""
    parser.add_argument("--skin", default="skin", help="skin reflectance set, name or CSV path (default skin)")
    parser.add_argument("--munsell", default="munsell", help="Munsell reflectance set, name or CSV path (default munsell)")
    parser.add_argument("--workers", type=int, help="processes (default: every core)")
    parser.add_argument("--dask", metavar="ADDRESS", help="run on a Dask cluster (scheduler address, tcp://host:8786)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar on stderr")


def add_render(parser: argparse.ArgumentParser, spp_auto: bool = False) -> None:
    """The Mitsuba options: quality, spp (``spp_auto``: also ``auto``), sampler, seed, variant, channels."""
    from ..rendering.settings import CHANNEL_GROUPINGS, QUALITY_PRESETS, SAMPLERS

    parser.add_argument("--quality", choices=list(QUALITY_PRESETS), default="standard",
                        help="preset: " + ", ".join(f"{k} ({v['spp']} spp)" for k, v in QUALITY_PRESETS.items())
                        + "; multijitter sampler; default standard")
    if spp_auto:
        parser.add_argument("--spp", help="samples per pixel (overrides --quality), or auto with --tolerance: the "
                            "smallest spp expected to pass, from two cheap pilot renders")
    else:
        parser.add_argument("--spp", type=int, help="samples per pixel (overrides --quality)")
    parser.add_argument("--sampler", choices=list(SAMPLERS), help="Mitsuba sampler: " + choices_help(SAMPLERS)
                        + "; default multijitter (independent for a chart at --physics subsurface-volume)")
    parser.add_argument("--seed", type=int, default=0, help="sampler seed; the same seed gives the same image (default 0)")
    parser.add_argument("--variant", help="force a Mitsuba variant (llvm_ad_spectral, cuda_ad_spectral, scalar_spectral); "
                        "default: the fastest that works here")
    parser.add_argument("--channels", choices=list(CHANNEL_GROUPINGS), default="auto",
                        help="render passes: " + choices_help(CHANNEL_GROUPINGS))
    parser.add_argument("--imager", help="record the render with an image sensor: a preset (see 'skinrender imagers') "
                        "or a TOML file; adds photon shot, dark and read noise, full well, gain and ADC")
    parser.add_argument("--illuminance", type=float, default=None,
                        help=f"with --imager (or a face's noise level): illuminance at the chart, lx (default "
                        f"{ILLUMINANCE_DEFAULT:g}, an office; a face: the scene's)")
    parser.add_argument("--exposure", default=None,
                        help="with --imager (or a face's noise level): exposure in s, or auto (the calibration "
                        "white's brightest channel at 0.7 of the full well; default)")
    add_max_minutes(parser, "the renders × pixels × --spp")


def add_max_minutes(parser: argparse.ArgumentParser, what: str) -> None:
    """``--max-minutes``: the cap on a run's estimated time (:mod:`skinrender.workload`); ``what`` scales it."""
    from ..workload import MINUTES_MAX

    parser.add_argument("--max-minutes", metavar="MIN", type=float, default=None,
                        help=f"refuse runs estimated to take longer than this, minutes (default {MINUTES_MAX:g}; the "
                        f"estimate, from {what}, is printed with the refusal)")


def emit(args, document: dict, text: str) -> None:
    """
    Print ``document`` as one JSON document (``--json``: ``args.json``, of the parsed arguments or of what a command
    made of them, or the flag itself) or ``text``. The document is made whole before a byte is written: one that
    cannot be (a NaN or infinity left in it) prints nothing, never half of it; every byte's write is checked
    (:func:`skinrender.files.write_stdout`: a full disk under ``> out.json`` is an error naming standard output,
    exit status 1, never a short document and status 0).
    """
    if args if isinstance(args, bool) else args.json:
        write_stdout(json.dumps(document, indent=2, allow_nan=False) + "\n")
    else:
        write_stdout(text.rstrip("\n") + "\n")


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
    """:func:`grid_from` ``--grid`` (the default grid for a command without it): the commands pass it on."""
    return grid_from(getattr(args, "grid", None))


def grid_from(text: str | None):
    """``--grid``'s :class:`~skinrender.spectra.WavelengthGrid` (``None``: the default grid)."""
    from ..spectra import GRID_DEFAULT, WavelengthGrid

    return GRID_DEFAULT if text is None else flag("--grid", WavelengthGrid.parse, text)


def settings_of(args: argparse.Namespace, auto: bool = False):
    """:func:`settings_from` the render flags (``--quality --spp --sampler --seed --variant --channels``)."""
    return settings_from(args.quality, args.spp, args.sampler, args.seed, args.variant, args.channels, auto)


def settings_from(quality: str, spp, sampler: str | None, seed: int, variant: str | None, channels: str,
                  auto: bool = False):
    """The :class:`~skinrender.rendering.settings.RenderSettings` of the render flags, made once per command:
    ``--quality``'s spp and sampler unless ``--spp`` or ``--sampler`` is given, ``--seed``, ``--variant`` (checked to
    run here before anything renders) and ``--channels``; each refusal names its flag. ``auto``: ``--spp auto``,
    which the command resolves itself (``validate``), the quality's spp standing in until it has."""
    from ..rendering.settings import QUALITY_PRESETS, RenderSettings

    preset = QUALITY_PRESETS[quality]
    spp = spp if spp is not None and not auto else preset["spp"]
    if isinstance(spp, str):  # a command whose --spp also takes auto (validate), which it resolves itself
        if spp.strip().lower() == "auto":
            raise SkinrenderError("--spp auto goes with a chart's 'validate --tolerance T'", flag="--spp")
        spp = integer_in(spp, "--spp", 1, SPP_MAX)
    if not 1 <= spp <= SPP_MAX:
        raise SkinrenderError(f"--spp must be an integer in [1, {SPP_MAX}], got {spp}", flag="--spp")
    return RenderSettings(spp, check_seed(seed), sampler or preset["sampler"], variant_of(variant), channels)


from ..rendering.settings import SEED_MAX, SPP_MAX  # noqa: E402 - every door's bounds (re-exported)


class Parser(argparse.ArgumentParser):
    """
    An argument parser whose errors are one line, ``skinrender COMMAND: error: …``, exit status 2; a command's
    parser carries ``run``, the function of the parsed arguments that runs the command (the command registry:
    ``commands.add_parser(NAME, run=FUNCTION, help=…)``, :func:`skinrender.cli.commands`).
    """

    def __init__(self, *args, run=None, **kwargs):
        super().__init__(*args, **kwargs)
        self.run = run

    def error(self, message: str):  # noqa: D102 - argparse's hook
        self.exit(2, f"{self.prog}: error: {message} (see '{self.prog} --help')\n")

    def _print_message(self, message: str, file=None) -> None:  # argparse's hook: --help and usage
        if message and (file is None or file is sys.stdout):
            write_stdout(message)  # checked: a full disk under `--help > f` is an error, not a short file
        elif message:
            super()._print_message(message, file)


flag = naming
"""``function(*args, **kwargs)`` with its error naming the flag: :func:`skinrender.errors.naming`."""


def flagged(flags: dict, function, *args, **kwargs):
    """
    ``function(*args, **kwargs)``, its :class:`SkinrenderError` worded with the flag of its ``role`` (``flags``:
    role → flag, the key ``None`` for any other role): a message that starts with the argument's name (``seed must
    be …``, ``imager: …``) starts with the flag instead (``--seed must be …``), any other is prefixed with it. An
    error that names its flag already, or whose role has no flag, is passed on as it is. How the command line
    words the refusals of a request (:mod:`skinrender.rendering.request`), which name the arguments from Python.

    >>> from skinrender.rendering.settings import RenderSettings
    >>> flagged({"seed": "--seed"}, RenderSettings, seed=-1)
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: --seed must be an integer in [0, 2^32) and at most 4294967294 (Mitsuba's seeds are 32-bit, and a chart's calibration render uses seed + 1), got -1
    """
    try:
        return function(*args, **kwargs)
    except SkinrenderError as error:
        name = flags.get(error.role, flags.get(None))
        if error.flag is not None or name is None:
            raise
        role, message = error.role or "", error.message
        if role and message.startswith(role) and message[len(role):len(role) + 1] in (" ", ":"):
            words = name + message[len(role):]
        else:
            words = f"{name}: {message}"
        raise error.reworded(words, flag=name) from None


def integer_in(text, name: str, low: int, high: int | None = None) -> int:
    """
    ``text`` as an integer in ``[low, high]`` (``high`` ``None``: no upper bound), else a one-line error naming
    the flag ``name``.

    >>> integer_in(" 12 ", "--size", 1, 2000), integer_in("7", "--samples", 1)
    (12, 7)
    """
    try:
        value = int(str(text).strip())
    except ValueError:
        value = None
    if value is None or value < low or (high is not None and value > high):
        bounds = f"≥ {low}" if high is None else f"in [{low}, {high}]"
        raise SkinrenderError(f"{name} must be an integer {bounds}, got {text!r}", flag=name)
    return value


def positive_number(text, name: str, unit: str, high: float | None = None) -> float:
    """
    ``text`` as a finite number > 0 (and ≤ ``high`` where given), else a one-line error naming the flag ``name``
    (``unit``: what it counts). ``--illuminance`` takes at most :data:`ILLUMINANCE_MAX` whatever ``high``.

    >>> positive_number("300", "--illuminance", "lx")
    300.0
    """
    try:
        value = float(text)
    except (TypeError, ValueError):
        value = math.nan
    high = ILLUMINANCE_MAX if high is None and name == "--illuminance" else high
    if not math.isfinite(value) or value <= 0 or (high is not None and value > high):
        bound = "" if high is None else f" and ≤ {high:g}"
        raise SkinrenderError(f"{name} must be a finite number > 0{bound} ({unit}), got {text!r}", flag=name)
    return value


from ..rendering.sensor import EXPOSURE_MAX, ILLUMINANCE_MAX  # noqa: E402, F401 - the sensor's bounds (re-exported)


def variant_of(name: str | None) -> str | None:
    """``--variant``: ``None``, or a spectral Mitsuba variant that runs here (checked before anything renders)."""
    if name is None:
        return None
    from ..rendering.variants import VARIANTS_SPECTRAL, choose_variant

    if name not in VARIANTS_SPECTRAL:
        raise SkinrenderError(f"--variant must be one of {', '.join(VARIANTS_SPECTRAL)}, got {name!r}",
                              flag="--variant")
    flag("--variant", choose_variant, name)
    return name


def check_output(path: str | None, name: str, suffixes: tuple[str, ...] = ()) -> Path | None:
    """
    Check an output file path before any work is done (nothing is left behind): the file it writes (a
    symbolic link to a file: its target), or ``None`` when the flag ``name`` was not given.

    Refused, with the flag ``name`` in the message: an empty path; a suffix not in ``suffixes``; an existing
    folder, pipe or device; a dangling symbolic link; a name too long; a parent that is a file; a place that
    cannot be written (:func:`skinrender.files.check_output_path`). A missing parent folder is fine (it is
    created on writing, and removed again when the writing fails).
    """
    if path is None:
        return None
    if not str(path).strip():
        raise SkinrenderError(f"{name}: expected a file path, got an empty one", flag=name)
    target = check_output_path(path, name)  # a folder, a link to nothing, a name too long … first
    if suffixes and Path(path).suffix.lower() not in suffixes:
        raise SkinrenderError(f"{name}: {shown(path)} must end in {' or '.join(suffixes)}", flag=name)
    return target


def check_seed(seed: int, name: str = "--seed") -> int:
    """A seed in ``[0, SEED_MAX]`` (:func:`skinrender.rendering.settings.check_seed`, every door's rule), else a
    one-line error naming the flag."""
    from ..rendering.settings import check_seed as checked

    return flagged({"seed": name}, checked, seed)


def camera_of(args: argparse.Namespace, grid=None, name: str = "--camera"):
    """:func:`camera_from` ``--camera`` (with ``--extrapolation`` where the command has it)."""
    spec = getattr(args, name.lstrip("-").replace("-", "_"))
    return camera_from(spec, getattr(args, "extrapolation", "refuse"), grid, name)


def camera_from(spec: str, extrapolation: str = "refuse", grid=None, name: str = "--camera"):
    """The camera of flag ``name`` (a CSV's with ``extrapolation``), its curves checked on ``grid``."""
    from ..model.camera import camera
    from ..spectra import GRID_DEFAULT

    cam = flag(name, camera, spec, extrapolation=extrapolation)
    flag(name, cam.sensitivities, grid or GRID_DEFAULT)
    return cam


def coverage_hint(error, args: argparse.Namespace) -> str:
    """
    The line of a refusal: for spectra that do not cover the grid (``cause`` ``coverage``), advice kept to the flags
    that apply (``--grid``; ``--extrapolation`` unless refused already, or for a bundled set); any other as it is.

    >>> import argparse
    >>> from skinrender.errors import SkinrenderError
    >>> coverage_hint(SkinrenderError("x.csv: measured over 420–680 nm, which does not cover the grid 400–700 nm",
    ...                               cause="coverage", hint="choose a grid inside the data"), argparse.Namespace())
    'x.csv: measured over 420–680 nm, which does not cover the grid 400–700 nm; this command integrates over that grid: give spectra that cover it'
    """
    if not isinstance(error, SkinrenderError) or error.cause != "coverage":
        return str(error)
    from ..datasets.registry import is_bundled

    message, grid, extrapolation = error.message, hasattr(args, "grid"), getattr(args, "extrapolation", None)
    bundled = is_bundled(message.split(": measured over")[0].split(": ")[-1])  # else a user's file
    if grid and extrapolation == "refuse" and bundled and not getattr(args, "extrapolates_named", False):
        return message + "; choose a --grid inside the data (a bundled set is not extrapolated)"
    if grid and extrapolation == "refuse":
        return message + "; choose a --grid inside the data or an --extrapolation ('zero' or 'constant')"
    if grid and extrapolation is not None:
        return (message + f"; choose a --grid inside the data (--extrapolation {extrapolation} applies to CSV "
                "files, not to these spectra)")
    if grid:
        return message + "; choose a --grid inside the data"
    return message + "; this command integrates over that grid: give spectra that cover it"


from ..rendering.request import ILLUMINANCE_DEFAULT  # noqa: E402 - a chart's, through --imager (re-exported)


def sensor_settings(args: argparse.Namespace, default_lux: float | None = ILLUMINANCE_DEFAULT) -> tuple:
    """
    ``--illuminance`` (lx; ``default_lux`` when not given) and ``--exposure`` (s or ``"auto"``) checked:
    ``(lux, exposure)``.

    >>> import argparse
    >>> sensor_settings(argparse.Namespace(illuminance=None, exposure="0.01"))
    (500.0, 0.01)
    """
    from ..rendering.sensor import NoiseOptions

    lux = default_lux if args.illuminance is None else args.illuminance
    options = flagged({"illuminance": "--illuminance", "exposure": "--exposure"}, NoiseOptions,
                      illuminance=lux, exposure="auto" if args.exposure is None else args.exposure)
    return options.illuminance, options.exposure


def refuse_sensor_settings(args: argparse.Namespace, instead: str = "--imager") -> None:
    """``--illuminance`` and ``--exposure`` set the image sensor: refused (one line) where there is none."""
    for name in ("illuminance", "exposure"):
        if getattr(args, name, None) is not None:
            raise SkinrenderError(f"--{name} sets the image sensor's exposure: it goes with {instead}", flag=f"--{name}")


def imaging_options(args: argparse.Namespace) -> dict | None:
    """``--imager``, ``--illuminance`` (lx) and ``--exposure`` (s or auto) checked, or ``None`` without ``--imager``
    (when ``--illuminance`` or ``--exposure`` is given without it, a one-line refusal)."""
    if args.imager is None:
        refuse_sensor_settings(args)
        return None
    from ..model.imager import imager

    sensor = flag("--imager", imager, args.imager)
    lux, exposure = sensor_settings(args)
    return {"imager_": sensor, "illuminance_lux": lux, "exposure": exposure}


def interruptible(command):
    """
    ``command`` (a function of the parsed arguments) run in a worker thread while the main thread waits, so that
    Ctrl-C stops it at once: Mitsuba renders in native code, where the main thread would take the interrupt only
    when the render returns (as late as the whole render: tens of seconds for a large face). The KeyboardInterrupt
    reaches :func:`skinrender.cli.main`, which exits 130 at once (``os._exit``: the worker is not waited for, and
    nothing is written after it). The command's own result or exception is passed on.
    """
    import functools
    import threading

    @functools.wraps(command)
    def run(*arguments) -> None:
        outcome: dict = {}

        def work() -> None:
            try:
                outcome["result"] = command(*arguments)
            except BaseException as error:  # noqa: BLE001 - handed to the main thread as it is
                outcome["error"] = error

        worker = threading.Thread(target=work, name="skinrender command", daemon=True)
        worker.start()
        while worker.is_alive():
            worker.join(0.1)  # wakes for signals: Ctrl-C raises KeyboardInterrupt here
        if "error" in outcome:
            raise outcome["error"]
        return outcome.get("result")

    return run
