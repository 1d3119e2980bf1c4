"""
Measure the fast subsurface transport (``--physics subsurface``, the slab's table as a BSDF) for
docs/subsurface.md, each figure with the load average beside it:

    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py table     # the table against adding-doubling at 64 points
    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py setup     # its one-off cost and its cost per sample
    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py ladder    # the default ladder: estimated and measured
    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py chart     # validate skin_patches --physics subsurface
    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py calibration [SEEDS SPP]  # its difference test's false alarms
    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py patches [SEEDS SPP]  # the same on skin_patches
    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py face [SIZE SPP]   # fast vs volumetric on the face
    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py effective [SIZE SPP]  # two layers vs one medium, fast
    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py sums [SIZE SPP]  # the skin's NCC of summed pixels
    PYTHONPATH=$PWD python tools/measure_fast_subsurface.py rough [SPP]     # media under a rough boundary, a sky

``face`` runs ``skinrender ladder --levels direct,subsurface,interreflection+subsurface,subsurface-volume`` for the
light, medium and dark skin of ``ladder --effects`` and prints, per tone, each level's eq4_shift (with its 95 %
upper bound) and TPR (of the replicates' mean image, and the detection verdict's with the noise separated), and the fast levels' differences from the volumetric reference (eq4_shift, TPR, the skin's
mean NCC): the volumetric level path traces every bounce, so ``interreflection+subsurface`` is its like for like.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import numpy as np

CAMERA = "gbell:9@450,540,610"
SKINS = {"light": 0.02, "medium": 0.13, "dark": 0.3}


def _load() -> str:
    return "load average " + ", ".join(f"{v:.2f}" for v in os.getloadavg())


def _skinrender(*arguments: str) -> tuple[dict, float]:
    """Run the command line with ``--json``; its document and wall seconds."""
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "skinrender", *arguments, "--json"], capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode not in (0, 1, 3):
        raise SystemExit(f"skinrender {' '.join(arguments)} failed ({done.returncode}): {done.stderr.strip()[-400:]}")
    return json.loads(done.stdout), seconds


def table() -> None:
    """The table (32 points, 64 cosines) against adding-doubling at 64 points, at its nodes."""
    from skinrender.datasets.adding_doubling import Slab, angular_reflectance
    from skinrender.datasets.skin_model import SkinParameters, reflectance_of_layers, skin_layers
    from skinrender.rendering.slab_table import table_of_layers

    lam = np.arange(400.0, 701.0, 5.0)
    for tone, melanin in SKINS.items():
        layers = skin_layers(lam, SkinParameters(melanin=melanin))
        tab = table_of_layers(layers, lam)
        fine = angular_reflectance([Slab(a.mu_a_per_mm, a.mu_s_per_mm, a.g, a.thickness_mm) for a in layers],
                                   quad_pts=64)
        mo, mi = np.meshgrid(fine.mu, fine.mu, indexing="ij")
        f = tab.value(mo, mi)
        rel = np.abs(f - fine.brdf) / fine.brdf
        inner = (mo > 0.2) & (mi > 0.2)
        albedo = np.pi * np.einsum("loi,o->li", f, fine.weights)
        exact = np.pi * np.einsum("loi,o->li", fine.brdf, fine.weights)
        x = np.linspace(0.0, 1.0, 20001)
        normal = np.pi * np.trapezoid(tab.value(x, 1.0) * 2 * x, x, axis=-1) + tab.nodes.specular[-1]
        q16 = reflectance_of_layers(layers)
        print(f"{tone} (melanin {melanin}): f vs 64 points: median |rel| {np.median(rel):.1e}, max {rel.max():.1e} "
              f"(both angles within 78° of the normal: max {rel[:, inner].max():.1e}); directional-hemispherical "
              f"reflectance max |rel| {np.max(np.abs(albedo / exact - 1)):.1e} (at normal incidence "
              f"{np.max(np.abs(albedo[:, -1] / exact[:, -1] - 1)):.1e}); the table integrated at normal incidence "
              f"vs its UR1 max |rel| {np.max(np.abs(normal / tab.ur1 - 1)):.1e}; UR1 at 32 vs 16 points max "
              f"|Δ| {np.max(np.abs(tab.ur1 - q16)):.1e}")


def setup() -> None:
    """A face render's first and later seconds at direct and subsurface, 128 px, 64 spp, the face's own skin."""
    from skinrender.rendering.face.render import render_face

    print(_load())
    for level in ("direct", "subsurface"):
        seconds = []
        for seed in range(4):
            start = time.perf_counter()
            render_face(CAMERA, "face", 2856, 5900, None, level, spp=64, seed=seed, size=128)
            seconds.append(time.perf_counter() - start)
        later = float(np.median(seconds[1:]))
        print(f"{level}: first render {seconds[0]:.2f} s, later {later:.2f} s ({128 * 128 * 64 / later:.3g} "
              "samples/s on the machine)")
    print(_load())


def ladder() -> None:
    """The default ladder (128 px, 64 spp, every default level): the estimate and the wall time."""
    from skinrender.rendering.face.effects import LEVELS_LADDER
    from skinrender.studies.face.ladder import REPLICATES_LADDER
    from skinrender.studies.face.sweep import estimate_seconds

    each = -(-64 // REPLICATES_LADDER)
    levels = [level for level in LEVELS_LADDER for _ in range(REPLICATES_LADDER)]
    estimate = estimate_seconds(len(levels), 128 * 128, each, 1, levels)
    before = _load()
    document, seconds = _skinrender("ladder", "--camera", CAMERA, "--prevailing", "2200", "--calibration", "5900")
    rows = ", ".join(f"{row['name']} {row['seconds']:.1f} s" for row in document["levels"])
    print(f"default ladder ({len(LEVELS_LADDER)} levels): estimated {estimate:.0f} s, measured {seconds:.0f} s "
          f"({before}; after: {_load()}); {rows}")


def chart(spp: int = 64) -> None:
    """validate skin_patches at subsurface: the verdicts, the largest relative error and the seconds."""
    before = _load()
    for tolerance in ("0.05", "0.02"):
        document, seconds = _skinrender("validate", "skin_patches", "--camera", CAMERA, "--prevailing", "2856",
                                        "--calibration", "5900", "--physics", "subsurface", "--spp", str(spp),
                                        "--tolerance", tolerance)
        errors = [abs(r - a) / a for p in document["patches"] if p.get("skin_model") is not None
                  for r, a in zip(p["rendered"], p["analytic"])]
        checks = document["checks"]
        print(f"validate skin_patches --physics subsurface --spp {spp} --tolerance {tolerance}: "
              f"{document['verdict']}, equivalence {checks['equivalence']['verdict']} (bound "
              f"{document['bound']:.4f}), difference {checks['difference']['verdict']}; largest |relative error| of "
              f"a skin value {max(errors):.4f}; {seconds:.0f} s, rendering {document['elapsed_s']:.1f} s ({before})")


SLABS = """
name = "slabs"
columns = 3
patch_px = 8
gap_px = 2
border_px = 0
""" + "".join(f'[[patch]]\nname = "{tone}"\nreflectance = "skin-model:melanin={melanin}"\nskin = true\n'
              for tone, melanin in SKINS.items())


def calibration(seeds: int = 200, spp: int = 16) -> None:
    """validate's difference test (α 0.01) over independent seeds of three slabs where the renderer is right:
    its false alarms, with the multijitter sampler (the chart's default at subsurface)."""
    import tempfile
    from pathlib import Path

    from skinrender.evaluation.verdict import binomial_interval
    from skinrender.rendering.validation import validate

    before = _load()
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "slabs.toml"
        path.write_text(SLABS)
        start, alarms, worst = time.perf_counter(), 0, []
        for seed in range(0, 2 * seeds, 2):  # the calibration render takes seed + 1
            result = validate(str(path), CAMERA, 2856, 5900, spp=spp, seed=seed, physics="subsurface",
                              tolerance=0.05)
            alarms += result.difference.outcome == "fail"
            worst.append(float(np.nanmax(np.abs(result.rendered - result.analytic) / result.sigma)))
    low, high = binomial_interval(alarms, seeds)
    print(f"difference test (α 0.01), 3 slabs at 8 × 8 px, {spp} spp, multijitter: {alarms}/{seeds} false alarms "
          f"(95 % interval {low:.3f}–{high:.3f}); largest |z| median {np.median(worst):.2f}, max {max(worst):.2f}; "
          f"{time.perf_counter() - start:.0f} s ({before})")


FACE_LEVELS = ("direct", "subsurface", "interreflection+subsurface", "subsurface-volume")
"""The levels compared on the face: the volumetric level path traces every bounce (light from the props and the
face itself reaches the skin), so the fast transport's like for like is ``interreflection+subsurface``."""


def patches(seeds: int = 40, spp: int = 64) -> None:
    """validate skin_patches --physics subsurface over seeds 0, 2, …: the difference test's alarms (family-wise
    α 0.01 over the chart's 93 values) where the renderer is right, in one process (the fits once)."""
    from skinrender.rendering.validation import validate

    before, start, alarms, worst = _load(), time.perf_counter(), [], []
    for seed in range(0, 2 * seeds, 2):
        result = validate("skin_patches", CAMERA, 2856, 5900, spp=spp, seed=seed, physics="subsurface",
                          tolerance=0.02)
        worst.append(float(np.nanmax(np.abs(result.rendered - result.analytic) / result.sigma)))
        if result.difference.outcome == "fail":
            alarms.append((seed, round(worst[-1], 2)))
    print(f"skin_patches at subsurface, {spp} spp, {seeds} seeds: difference alarms {alarms or 'none'}; largest |z| "
          f"median {np.median(worst):.2f}, max {max(worst):.2f}; {time.perf_counter() - start:.0f} s ({before})")


def face(size: int = 32, spp: int = 48) -> None:
    """The fast level against the volumetric reference on the face, per skin tone (a ladder each)."""
    from skinrender.studies.face.effects_table import SKIN_TONES

    print(f"ladder --levels {','.join(FACE_LEVELS)} --size {size} --spp {spp}, per tone ({_load()})")
    for tone, skin in SKIN_TONES.items():
        document, seconds = _skinrender("ladder", "--skin", skin, "--levels", ",".join(FACE_LEVELS),
                                        "--camera", CAMERA, "--prevailing", "2856", "--calibration", "5900",
                                        "--size", str(size), "--spp", str(spp), "--max-minutes", "120")
        rows = {row["name"]: row for row in document["levels"]}
        line = [f"{tone} ({skin}, budget {document['budget']['budget']:.4f})"]
        for level in FACE_LEVELS:
            row = rows[level]
            separated = (row.get("detection") or {}).get("tpr")
            line.append(f"{level}: eq4_shift {row['eq4_shift']:.4f} (≤ {row['eq4_shift_bound']:.4f}), "
                        f"TPR {row['tpr']:.3f} (noise separated {'—' if separated is None else f'{separated:.3f}'}), "
                        f"{row['seconds']:.1f} s")
        volume = rows["subsurface-volume"]
        for level in FACE_LEVELS[1:3]:
            fast = rows[level]
            apart = np.subtract(fast["skin_ncc_mean"], volume["skin_ncc_mean"])[:2]
            line.append(f"{level} − volume: eq4_shift {fast['eq4_shift'] - volume['eq4_shift']:+.4f}, TPR "
                        f"{fast['tpr'] - volume['tpr']:+.3f}, mean skin NCC (r, g) {apart[0]:+.4f} {apart[1]:+.4f}")
        print("; ".join(line) + f" [{seconds:.0f} s, {_load()}]")


def effective(size: int = 64, spp: int = 64) -> None:
    """The fast level on the face with the table of the skin's two layers and with the table of the volumetric
    level's one effective medium (the same UR1), at interreflection+subsurface: what the effective medium alone
    moves the skin's mean NCC by."""
    from unittest import mock

    from skinrender.model.chromaticity import ncc
    from skinrender.rendering.face import render_face
    from skinrender.rendering.face.effects import subsurface_table
    from skinrender.rendering.loaded import release_scenes
    from skinrender.rendering.slab_table import slab_table, table_of_layers
    from skinrender.rendering.subsurface import effective_layer, skin_media_of
    from skinrender.studies.face.effects_table import SKIN_TONES

    print(f"interreflection+subsurface, {size} px, {spp} spp, two layers vs one effective medium ({_load()})")
    for tone, skin in SKIN_TONES.items():
        means = {}
        for name in ("two layers", "one medium"):
            def table(spec, grid, where="skin"):
                if name == "two layers":
                    return slab_table(spec, grid, where)
                media = skin_media_of(spec, grid, where)
                return table_of_layers((effective_layer(media.layers),), grid.wavelengths)

            release_scenes()  # the face's loaded document holds the other table
            with mock.patch.object(subsurface_table, "slab_table", table):
                result = render_face(CAMERA, "face", 2856, 5900, skin, "interreflection+subsurface", spp=spp,
                                     seed=0, size=size)
            skin_pixels = result.image[result.labels == 1]
            means[name] = ncc(skin_pixels).mean(axis=0)[:2]
        apart = means["two layers"] - means["one medium"]
        print(f"{tone} ({skin}): mean skin NCC (r, g) two layers {means['two layers'].round(4).tolist()}, one medium "
              f"{means['one medium'].round(4).tolist()}, two − one {apart[0]:+.4f} {apart[1]:+.4f}")


def sums(size: int = 32, spp: int = 128) -> None:
    """The skin's NCC from its summed pixels (ratio of sums, which per-pixel noise does not bias) beside the mean of
    its pixels' NCC, at interreflection+subsurface and subsurface-volume, light and dark skin, one render each."""
    from skinrender.model.chromaticity import ncc
    from skinrender.rendering.face import render_face
    from skinrender.studies.face.effects_table import SKIN_TONES

    print(f"{size} px, {spp} spp, seed 0 ({_load()})")
    for tone in ("light", "dark"):
        for level in ("interreflection+subsurface", "subsurface-volume"):
            start = time.perf_counter()
            result = render_face(CAMERA, "face", 2856, 5900, SKIN_TONES[tone], level, spp=spp, seed=0, size=size)
            pixels = result.image[result.labels == 1]
            print(f"{tone}, {level}: NCC (r, g) of the summed skin pixels {ncc(pixels.sum(axis=0))[:2].round(4).tolist()}"
                  f", mean of the pixels' {ncc(pixels).mean(axis=0)[:2].round(4).tolist()}; "
                  f"{time.perf_counter() - start:.0f} s")


def rough(spp: int = 64) -> None:
    """
    The volumetric slab of the chart (two layers, at the origin, under a uniform sky, seen along the normal,
    ``skinvolpath``) with its top boundary smooth (the chart's: its pixel is UR1) and rough (GGX α 0.35, the
    face's) as Mitsuba has it and with its lost light put back (``skinrender.rendering.rough_boundary``): each
    channel's mean over adding-doubling's UR1, minus 1; then the white furnace: the same layers with no absorption,
    0.6 mm thick, both faces the top's, inside the sky on every side (no floor), whose pixel is the sky's radiance
    exactly when every boundary conserves energy, whatever its roughness. A rough dielectric of one scattering off
    microfacets (Mitsuba's ``roughdielectric``) loses the light its microfacets would scatter again, at every
    crossing and internal reflection, and light in skin meets its boundary from inside many times.
    """
    from dataclasses import replace

    from skinrender.datasets.skin_model import SkinParameters, skin_layers
    from skinrender.model.camera import camera
    from skinrender.rendering.face.document import channel_integral
    from skinrender.rendering.face.effects.subsurface import SUBSURFACE_ALPHA
    from skinrender.rendering.renderer import emitter_grid
    from skinrender.rendering.skin_integrator import register
    from skinrender.rendering.subsurface import SkinMedia, slab_reflectance, subsurface_variant
    from skinrender.rendering.subsurface_chart import slab_document
    from skinrender.rendering.variants import mitsuba

    from skinrender.spectra import GRID_DEFAULT, planck

    mi, grid, cam = mitsuba(subsurface_variant()), GRID_DEFAULT, camera(CAMERA)
    register(mi)
    t = mi.ScalarTransform4f
    lam = emitter_grid(grid)
    sky = planck(lam, 2856.0)
    sky = sky / sky.max()
    print(f"the chart's slab at the origin under a uniform sky, 16 × 16 px, {spp} spp, skinvolpath ({_load()})")
    for tone, melanin in SKINS.items():
        layers = skin_layers(grid.wavelengths, SkinParameters(melanin=melanin))
        for furnace in (False, True):
            if furnace:
                layers = tuple(replace(layer, mu_a_per_mm=np.zeros_like(layer.mu_a_per_mm)) for layer in layers)
                expected = channel_integral(cam, grid, lam, sky)
            else:
                expected = channel_integral(cam, grid, lam, np.interp(lam, grid.wavelengths,
                                                                      slab_reflectance(layers)) * sky)
            media = SkinMedia(f"melanin {melanin}", None, None, layers, grid.wavelengths)
            for alpha, compensated in ((0.0, False), (SUBSURFACE_ALPHA, False), (SUBSURFACE_ALPHA, True)):
                document = slab_document(mi, media, None, cam, grid, (0, 1, 2), 16, spp, "independent", sky)
                if alpha > 0:
                    document["top"]["bsdf"] = {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha,
                                               "int_ior": float(layers[0].n), "ext_ior": 1.0}
                    document["integrator"]["boundary_alpha"] = alpha if compensated else 0.0
                if furnace:  # both faces alike (a smooth face's crossings carry no radiance factor η²), no floor
                    del document["floor"]
                    document["bottom"].update(bsdf=document["top"]["bsdf"], interior=document["top"]["interior"])
                    document["bottom"]["to_world"] = (t().translate([0, 0, -0.6]) @ t().rotate([1, 0, 0], 180)
                                                      @ t().scale([1000.0, 1000.0, 1.0]))
                start = time.perf_counter()
                image = np.array(mi.render(mi.load_dict(document), seed=1), dtype=np.float64).reshape(-1, 3)
                mean, se = image.mean(axis=0), image.std(axis=0, ddof=1) / np.sqrt(len(image))
                what = "white furnace (no absorption, 0.6 mm, no floor): mean/sky" if furnace else "mean/UR1"
                top = "smooth" if alpha == 0 else f"GGX α {alpha}{', compensated' if compensated else ''}"
                print(f"{tone}, top boundary {top}, {what} − 1 "
                      f"{np.round(mean / expected - 1, 4).tolist()} (± {np.round(2 * se / expected, 4).tolist()} at "
                      f"2 SE); {time.perf_counter() - start:.0f} s ({_load()})", flush=True)


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else ""
    numbers = [int(v) for v in sys.argv[2:]]
    tasks = {"table": table, "setup": setup, "ladder": ladder, "chart": chart, "calibration": calibration,
             "patches": patches, "face": face, "effective": effective, "sums": sums, "rough": rough}
    if what not in tasks:
        raise SystemExit(__doc__)
    tasks[what](*numbers)
