"""
The spectral bench's figure
===========================

:func:`figure_spectral` draws ``skinrender bench render --spectral --plot``
(:mod:`skinrender.studies.benchmarks.bench_spectral`): the face sweep's seconds
against the number of cameras, spectral and one render per camera, with the
speedup at equal error; each channel's error both ways, for the broad
cameras and the narrow one (the penalty of uniform wavelength sampling); and
the basis error against the band step. It draws with
:mod:`skinrender.studies.figures`' helpers (one style, one place that imports
matplotlib).

Units: seconds s; errors relative; band steps nm.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..figures import pyplot_agg, save_figure

__all__ = ["figure_spectral"]


def figure_spectral(result: dict, path: str | Path) -> Path:
    """The bench's three panels (module docstring) from its JSON document ``result``; a PNG at ``path``."""
    plt = pyplot_agg()
    figure, (time_axis, error_axis, basis_axis) = plt.subplots(1, 3, figsize=(15, 4.4))
    rows = result["rows"]
    counts = [row["cameras"] for row in rows]
    time_axis.loglog(counts, [row["direct_s"] for row in rows], "o-", label="one render per camera")
    time_axis.loglog(counts, [row["spectral_s"] for row in rows], "s-", label="spectral, seen through each")
    for row in rows:
        time_axis.annotate(f"{row['speedup']:.1f}×", (row["cameras"], row["spectral_s"]), fontsize=7,
                           xytext=(3, -10), textcoords="offset points")
    time_axis.set(xlabel="cameras", ylabel="face sweep, s (one worker)",
                  title=f"{len(result['lights_K'])} light pairs × {len(result['skins'])} skins × "
                        f"{len(result['levels'])} levels, {result['size']} px, {result['spp']} spp")
    time_axis.legend(fontsize=7)
    channels = np.arange(3)
    broad_s, broad_d = np.array(result["errors"]["spectral"]), np.array(result["errors"]["direct"])
    narrow = result["narrow"]
    for offset, values, label in ((-0.3, np.sqrt(np.mean(broad_d**2, axis=0)), "broad, direct"),
                                  (-0.1, np.sqrt(np.mean(broad_s**2, axis=0)), "broad, spectral"),
                                  (0.1, narrow["error_direct"], f"{narrow['camera']}, direct"),
                                  (0.3, narrow["error_spectral"], f"{narrow['camera']}, spectral")):
        error_axis.bar(channels + offset, values, width=0.2, label=label)
    error_axis.set_xticks(channels, ["R", "G", "B"])
    error_axis.set(ylabel=f"RMS relative error of skin pixels at {result['spp']} spp",
                   title="error at equal spp (narrow penalty: " + ", ".join(f"{p:.1f}×" for p in narrow["penalty"])
                         + ")")
    error_axis.legend(fontsize=7)
    for name in dict.fromkeys(row["camera"] for row in result["basis"]):
        mine = [row for row in result["basis"] if row["camera"] == name]
        steps = [float(row["bands_nm"].split(":")[-1]) for row in mine]
        basis_axis.loglog(steps, [max(row["max_rel_error"], 1e-9) for row in mine], "o-", label=name)
    basis_axis.set(xlabel="band step, nm", ylabel="largest relative Eq. 4 error (Macbeth)",
                   title="basis error of curves off the band grid")
    basis_axis.legend(fontsize=6)
    return save_figure(figure, path)
