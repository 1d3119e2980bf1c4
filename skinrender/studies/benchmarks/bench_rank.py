"""
The ranking's speed
===================

``skinrender bench rank``: the issue's configuration of ``skinrender rank`` —
20 candidates (the Stage 3 search's top 20 at sensor 9, 400–700 nm every 20
nm), 4 light pairs, 3 skin tones and the five fast levels at 64 px, 16 spp —
timed end to end (the search and the renders), against its target of 10
minutes on 2 cores; ``--quick``: 4 candidates, 1 light pair, 1 skin, 2 levels.

-   :func:`bench_rank`: the measurement; :data:`TARGET_S`.

Units: seconds s.
"""

from __future__ import annotations

import os
import time

from ..face.effects_table import SKIN_TONES
from ..face.ranking import LEVELS_RANK, rank, search_candidates
from .bench import machine

__all__ = ["TARGET_S", "bench_rank"]

TARGET_S = 600.0
"""The target: the full configuration within 10 minutes on 2 cores."""

LIGHTS_RANK = ((2300.0, 5900.0), (2856.0, 5900.0), (5900.0, 5900.0), (10000.0, 5900.0))
"""The light pairs (face-sweep's default)."""


def bench_rank(quick: bool = False, workers: int | None = None, progress=None) -> dict:
    """
    Time ``rank`` on the issue's configuration (``quick``: a small one), s.

    Returns
    -------
    dict
        ``machine``, ``load_average`` (1, 5, 15 min, before and after), ``candidates``, ``lights``, ``skins``,
        ``levels``, ``size``, ``spp``, ``search_s``, ``rank_s``, ``seconds``, ``target_s``, ``within_target``
        (on a machine of 2 cores; ``None`` on another), the ranking's per-level ``kendall_tau`` and the whole
        ``ranking`` (``rank``'s document).
    """
    top = 4 if quick else 20
    lights = LIGHTS_RANK[1:2] if quick else LIGHTS_RANK
    skins = list(SKIN_TONES.values())[:1] if quick else list(SKIN_TONES.values())
    levels = LEVELS_RANK[:2] if quick else LEVELS_RANK
    before = os.getloadavg()
    start = time.perf_counter()
    cameras = search_candidates(top, 9.0, "400:700:20", workers=workers, progress=progress)
    searched = time.perf_counter()
    result = rank(cameras, lights, skins, levels, size=64, spp=16, workers=workers, progress=progress)
    end = time.perf_counter()
    cores = os.cpu_count()
    return {"machine": machine(), "load_average": {"before": list(before), "after": list(os.getloadavg())},
            "quick": quick, "candidates": len(cameras), "lights": len(lights), "skins": len(skins),
            "levels": list(levels), "size": 64, "spp": result.spp, "workers": result.workers,
            "search_s": searched - start, "rank_s": end - searched, "seconds": end - start, "target_s": TARGET_S,
            "within_target": (end - start <= TARGET_S) if cores == 2 and not quick else None,
            "kendall_tau": {level["level"]: level["kendall_tau"] for level in result.levels},
            "ranking": result.document()}
