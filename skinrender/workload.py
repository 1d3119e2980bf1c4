"""
Work that grows with a count
============================

Every count a user gives that scales the work (samples, repetitions,
evaluations, levels × pixels × spp, triplets, renders) is checked against an
estimate of its time before anything runs: above the cap the command refuses
with one line naming the flag, the estimate and the flag that raises the cap,
the pattern of ``search --max-triplets`` and ``face-sweep --max-renders``.

-   :data:`MINUTES_MAX`: the default cap of the commands' ``--max-minutes``.
-   :func:`duration_text`: seconds as a person reads them (``3.2 s``, ``14 min``,
    ``2.1 h``, ``3.5 days``).
-   :func:`check_work`: the refusal.
-   :func:`progress_bar`, :func:`announce`: the progress of long work on
    stderr, a bar on a terminal and one line elsewhere.

The rates behind the estimates are measured on the development machine (a
2-core AMD EPYC VM shared with other jobs) and stated where each is defined;
an estimate is a guide to the order of magnitude, not a promise.
"""

from __future__ import annotations

import math

from .errors import SkinrenderError

__all__ = ["MINUTES_MAX", "duration_text", "check_work", "progress_bar", "announce"]

MINUTES_MAX = 60.0
"""Longest estimated run a command starts unless ``--max-minutes`` raises it, minutes."""


def duration_text(seconds: float) -> str:
    """
    ``seconds`` in the unit a person reads best.

    >>> duration_text(3.24), duration_text(840), duration_text(7560), duration_text(3.1e5)
    ('3.2 s', '14 min', '2.1 h', '3.6 days')
    """
    if not math.isfinite(seconds):
        return "forever"
    for unit, size in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= 2 * size if unit == "days" else seconds >= size:
            value = seconds / size
            return f"{value:.2g} {unit}" if value < 10 else f"{value:.0f} {unit}"
    return f"{seconds:.2g} s" if seconds < 10 else f"{seconds:.0f} s"


def check_work(seconds: float, flag: str, what: str, limit_minutes: float | None = None,
               override: str = "--max-minutes", fewer: str = "") -> None:
    """
    Refuse work whose estimate exceeds ``limit_minutes``.

    Parameters
    ----------
    seconds
        The estimated time, s.
    flag
        The flag whose count makes the work (named first in the message).
    what
        The work in words, e.g. ``"1e8 noisy samples per pixel"``.
    limit_minutes
        The cap, min (``--max-minutes``); ``None``: :data:`MINUTES_MAX`.
    override
        The flag that raises the cap.
    fewer
        What to lower instead, e.g. ``"fewer --samples"``.

    Raises
    ------
    SkinrenderError
        ``FLAG: WHAT would take about T (estimated), more than the cap of M min; raise OVERRIDE or …``.

    Examples
    --------
    >>> check_work(30.0, "--samples", "16 samples")
    >>> check_work(3.6e6, "--samples", "1e8 samples", fewer="ask for fewer --samples")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: --samples: 1e8 samples would take about 42 days (estimated), more than the cap of 60 min; raise --max-minutes or ask for fewer --samples
    """
    limit_minutes = MINUTES_MAX if limit_minutes is None else limit_minutes
    if not (math.isfinite(limit_minutes) and limit_minutes > 0):
        raise SkinrenderError(f"{override} must be a finite number of minutes > 0, got {limit_minutes!r}",
                              flag=override)
    if seconds > 60.0 * limit_minutes:
        raise SkinrenderError(f"{flag}: {what} would take about {duration_text(seconds)} (estimated), more than the "
                              f"cap of {limit_minutes:g} min; raise {override}" + (f" or {fewer}" if fewer else ""),
                              flag=flag, role="work")


def progress_bar(total: int, label: str, stream, unit: str = "triplet"):
    """
    A tqdm progress bar of ``total`` units (``unit``) on ``stream``, disabled when ``stream`` is ``None`` (``--quiet``)
    or not a terminal (a log file, a pipe, CI: there :func:`announce` says the work started).
    """
    from tqdm import tqdm

    enabled = stream is not None and getattr(stream, "isatty", lambda: False)()
    return tqdm(total=total, desc=label, file=stream, disable=not enabled, unit=unit, leave=True)


def announce(stream, label: str, total: int, unit: str = "triplet") -> None:
    """
    One line on a progress ``stream`` that is not a terminal (where no bar is drawn) saying the work started:
    ``label: total units …`` (nothing on a terminal, or without a stream).

    >>> import io
    >>> log = io.StringIO(); announce(log, "sensor 9", 4495); log.getvalue().strip()
    'sensor 9: 4495 triplets …'
    """
    if stream is not None and not getattr(stream, "isatty", lambda: False)():
        print(f"{label}: {total} {unit}{'s' * (total != 1)} …", file=stream, flush=True)
