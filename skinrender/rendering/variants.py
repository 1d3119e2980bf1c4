"""
Mitsuba variants
================

Picks the fastest spectral Mitsuba 3 variant that works on this machine:
``cuda_ad_spectral`` where an NVIDIA GPU answers, ``llvm_ad_spectral`` where a
libLLVM 16 or newer is found, else ``scalar_spectral`` (about 7× slower) with a
one-line notice on stderr.

drjit aborts the whole process (it does not raise) when its LLVM backend meets
too old a libLLVM (Debian 12's libllvm15: "Cannot select … fmaximum"), so
each candidate is first tried in a child process. ``DRJIT_LIBLLVM_PATH`` is set
to the newest libLLVM ≥ 16 found in the usual places unless the user set it.

The verdicts of those trials are left in the environment
(:data:`VERDICTS_VARIABLE`) for the processes this one starts (pool workers, a
CLI run from a script), so that one trial serves a whole session. Each verdict
is bound to a fingerprint of what decides it (host, interpreter, the installed
mitsuba and drjit, the libLLVM file, the environment variables drjit and CUDA
read): a child whose fingerprint differs (another machine, another install,
a library replaced since) tries the variant again.

-   :func:`choose_variant`: the variant to use (cached per process).
-   :func:`libllvm_path`: the libLLVM drjit will load, or ``None``.
-   :func:`mitsuba`: the ``mitsuba`` module with the chosen variant set.
"""

from __future__ import annotations

import glob
import hashlib
import importlib.util
import os
import re
import shutil
import socket
import subprocess
import sys

from ..errors import SkinrenderError
from ..extras import require

__all__ = ["VARIANTS_SPECTRAL", "LIBLLVM_MINIMUM", "ROUNDED", "VERDICTS_VARIABLE", "libllvm_path", "fingerprint",
           "variant_works", "choose_variant", "mitsuba", "rounded_note"]

ROUNDED: list[int] = []
"""Sample counts a Mitsuba sampler rounded a render's spp up to in this process (its "Sample count rounded up"
warnings, captured rather than printed: :func:`rounded_note` says it once)."""

VARIANTS_SPECTRAL = ("cuda_ad_spectral", "llvm_ad_spectral", "scalar_spectral")
"""Spectral variants, fastest first."""

LIBLLVM_MINIMUM = 16
"""Oldest libLLVM major version drjit's LLVM backend works with."""

_LIBLLVM_PATTERNS = (
    "/usr/lib/x86_64-linux-gnu/libLLVM.so.*",
    "/usr/lib/x86_64-linux-gnu/libLLVM-*.so*",
    "/usr/lib/llvm-*/lib/libLLVM*.so*",
    "/usr/lib/aarch64-linux-gnu/libLLVM*.so*",
    "/usr/lib64/libLLVM*.so*",
    "/opt/homebrew/opt/llvm/lib/libLLVM.dylib",
)

_CHOSEN: dict[str | None, str] = {}


def libllvm_path() -> str | None:
    """
    The libLLVM that drjit will load: ``DRJIT_LIBLLVM_PATH`` if set, else the
    newest libLLVM ≥ :data:`LIBLLVM_MINIMUM` found (and then set in the
    environment), else ``None``.
    """

    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        return os.environ["DRJIT_LIBLLVM_PATH"]
    best: tuple[int, str] | None = None
    for pattern in _LIBLLVM_PATTERNS:
        for path in glob.glob(pattern):
            match = re.search(r"LLVM[.-](?:so\.)?(\d+)", os.path.basename(path)) or re.search(r"llvm-(\d+)", path)
            if match and int(match.group(1)) >= LIBLLVM_MINIMUM and (best is None or int(match.group(1)) > best[0]):
                best = (int(match.group(1)), path)
    if best is None:
        return None
    os.environ["DRJIT_LIBLLVM_PATH"] = best[1]
    return best[1]


_PROBE = (
    "import mitsuba as mi, sys\n"
    "mi.set_variant(sys.argv[1])\n"
    "scene = mi.load_dict({'type': 'scene', 'integrator': {'type': 'direct'},\n"
    "    'sensor': {'type': 'orthographic', 'sampler': {'type': 'independent', 'sample_count': 4},\n"
    "               'film': {'type': 'specfilm', 'width': 2, 'height': 2, 'component_format': 'float32',\n"
    "                        'rfilter': {'type': 'box'},\n"
    "                        'c': {'type': 'irregular', 'wavelengths': '400, 700', 'values': '1, 1'}}},\n"
    "    'light': {'type': 'constant', 'radiance': {'type': 'blackbody', 'temperature': 3000.0}}})\n"
    "print(mi.render(scene))\n"
)
"""A tiny specfilm render with a blackbody: what skinrender needs, and what
drjit aborts on with too old a libLLVM."""


VERDICTS_VARIABLE = "SKINRENDER_VARIANT_VERDICTS"
"""Environment variable holding this session's probe verdicts, ``FINGERPRINT variant=1 variant=0 …``: set by the
process that ran the probes, read by the processes it starts (see :func:`fingerprint`)."""


def _stat(path: str | None) -> str:
    """Device, inode, size and modification time of ``path`` (followed to its file), or ``-``."""
    try:
        info = os.stat(path) if path else None
    except OSError:
        info = None
    return "-" if info is None else f"{info.st_dev}:{info.st_ino}:{info.st_size}:{info.st_mtime_ns}"


def fingerprint() -> str:
    """
    What a variant's probe verdict depends on, hashed: the host (and its boot), the interpreter, the installed
    ``mitsuba`` and ``drjit`` packages (their modules' and libraries' identity and times), the libLLVM drjit loads (the file's) and
    every ``DRJIT_*``, ``MI_*``, ``CUDA_*`` and ``LD_*`` environment variable. A verdict is only trusted under
    the same fingerprint, so a reinstall, a replaced library or another machine means a new probe.
    """
    llvm = libllvm_path()
    parts = [socket.gethostname(), sys.executable, sys.version, _stat(sys.executable), llvm or "-", _stat(llvm)]
    try:
        with open("/proc/sys/kernel/random/boot_id", encoding="ascii") as handle:
            parts.append(handle.read().strip())
    except OSError:
        pass
    for package in ("mitsuba", "drjit"):  # their modules and libraries, not __pycache__ (written on first import)
        spec = importlib.util.find_spec(package)
        folder = os.path.dirname(spec.origin) if spec is not None and spec.origin else None
        files = sorted(glob.glob(os.path.join(glob.escape(folder), "*.[ps][yo]*"))) if folder else []
        parts += [folder or "-", *(f"{os.path.basename(f)}={_stat(f)}" for f in files)]
    parts += sorted(f"{k}={v}" for k, v in os.environ.items()
                    if k.startswith(("DRJIT_", "MI_", "CUDA_", "LD_")))
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()[:32]


def _verdicts(key: str) -> dict[str, bool]:
    """The verdicts in the environment, where they were made under fingerprint ``key``; else none."""
    fields = os.environ.get(VERDICTS_VARIABLE, "").split()
    if not fields or fields[0] != key:
        return {}
    pairs = (field.partition("=") for field in fields[1:])
    return {variant: value == "1" for variant, sign, value in pairs if sign and value in ("0", "1")}


def variant_works(variant: str) -> bool:
    """
    Whether ``variant`` renders a tiny specfilm scene in a child process on this machine.

    The verdict is left in :data:`VERDICTS_VARIABLE` for the processes this one starts, which take it instead
    of probing again only under the same :func:`fingerprint`.
    """
    if variant.startswith("cuda") and not (shutil.which("nvidia-smi") or os.path.exists("/dev/nvidia0")):
        return False
    if variant.startswith("llvm") and libllvm_path() is None:
        return False
    key = fingerprint()
    known = _verdicts(key)
    if variant in known:
        return known[variant]
    try:
        done = subprocess.run([sys.executable, "-c", _PROBE, variant], capture_output=True, text=True,
                              timeout=180, env=os.environ.copy())
    except (OSError, subprocess.TimeoutExpired):
        return False  # perhaps a busy machine: not recorded, a child tries again
    works = known[variant] = done.returncode == 0
    os.environ[VERDICTS_VARIABLE] = " ".join([key, *(f"{name}={int(ok)}" for name, ok in sorted(known.items()))])
    return works


def choose_variant(requested: str | None = None, notice=sys.stderr) -> str:
    """
    The Mitsuba variant to render with.

    Parameters
    ----------
    requested
        A variant name to force (``llvm_ad_spectral`` …), or ``None`` for the
        fastest that works here.
    notice
        Stream for the one-line notice when falling back to ``scalar_spectral``.

    Raises
    ------
    SkinrenderError
        Mitsuba is not installed, the requested variant is not spectral or
        not in this build, or it does not run here (the reason is named).
    """

    if requested in _CHOSEN:
        return _CHOSEN[requested]
    require("render", "rendering")
    libllvm_path()  # before drjit is imported anywhere
    if requested is not None:
        if requested not in VARIANTS_SPECTRAL:
            raise SkinrenderError(f"variant must be one of {', '.join(VARIANTS_SPECTRAL)} (spectral), got {requested!r}")
        if not variant_works(requested):
            hint = ""
            if requested.startswith("llvm"):
                hint = (f" (it needs libLLVM ≥ {LIBLLVM_MINIMUM}: on Debian/Ubuntu 'apt-get install libllvm19', or set "
                        "DRJIT_LIBLLVM_PATH)")
            elif requested.startswith("cuda"):
                hint = " (it needs an NVIDIA GPU and driver)"
            raise SkinrenderError(f"variant {requested} does not run on this machine{hint}")
        _CHOSEN[requested] = requested
        return requested
    for variant in VARIANTS_SPECTRAL:
        if variant_works(variant):
            if variant == "scalar_spectral" and notice is not None:
                print(
                    "skinrender: notice: llvm_ad_spectral unavailable (needs libLLVM ≥ 16, e.g. Debian 'libllvm19'); "
                    "rendering with scalar_spectral, about 7× slower",
                    file=notice,
                )
            _CHOSEN[None] = variant
            return variant
    raise SkinrenderError("no spectral Mitsuba variant runs on this machine (tried " + ", ".join(VARIANTS_SPECTRAL) + ")")


def mitsuba(variant: str):
    """The ``mitsuba`` module with ``variant`` set."""
    libllvm_path()
    import mitsuba as mi

    if mi.variant() != variant:
        mi.set_variant(variant)
    _log_to_stderr(mi)
    return mi


_LOGGING: list = []


def _log_to_stderr(mi) -> None:
    """Mitsuba's log (e.g. "Sample count rounded up") to stderr, never stdout, which is the JSON's."""
    if _LOGGING:
        return

    class StderrAppender(mi.Appender):
        def append(self, level, text):
            rounded = re.search(r"Sample count rounded up to (\d+)", text)
            if rounded:  # one per render pass: summarised once at the end (rounded_note)
                ROUNDED.append(int(rounded[1]))
            else:
                print(text, file=sys.stderr)

        def log_progress(self, progress, name, formatted, eta, ptr=None):
            pass

    logger = mi.logger() if hasattr(mi, "logger") else mi.Thread.thread().logger()
    logger.clear_appenders()
    appender = StderrAppender()
    logger.add_appender(appender)
    _LOGGING.append(appender)  # kept alive: the logger holds it by reference


def rounded_note() -> str | None:
    """
    One line for every "Sample count rounded up" of this process (:data:`ROUNDED`), or ``None``.

    >>> ROUNDED[:] = [8, 8, 36]
    >>> rounded_note()
    "the sampler rounded the samples per pixel up to 8, 36 (3 render passes; multijitter takes a product of two integers): each JSON's 'spp' is the count used"
    >>> ROUNDED.clear()
    """
    if not ROUNDED:
        return None
    counts = ", ".join(str(n) for n in sorted(set(ROUNDED)))
    passes = f"{len(ROUNDED)} render pass{'es' * (len(ROUNDED) > 1)}"
    return (f"the sampler rounded the samples per pixel up to {counts} ({passes}; multijitter takes a product of two "
            "integers): each JSON's 'spp' is the count used")
