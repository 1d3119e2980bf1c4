"""
Scenes for tools/measure_skin_integrator.py (run that script: face, curvature, chart, noise).

-   face: the face at the subsurface-volume level at its place and moved by +100 mm (x): eq4_shift and TPR, each with
    its interval, and whether the two differ (independent seeds).
-   curvature: a sphere of skin under the uniform sky, seen at its top: the layers by depth (re-anchored, the
    face's; and from the last contact alone) against the same sphere with an offset sphere as the layers'
    boundary, and that against the flat slab.
-   chart [SPP]: ``skinrender validate skin_patches --physics subsurface-volume --tolerance 0.05`` timed (wall, CPU).
-   noise: the face's skin at the spp users run, the ladder's numbers, with and without the connections through
    the boundary to the point lights.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import time

import numpy as np
from scipy import stats

CAMERA = "gbell:9@450,540,610"


def _load() -> str:
    return "load " + " ".join(f"{v:.1f}" for v in os.getloadavg())


def _face_at(translate, seeds, size: int, spp: int, skin: str | None = None):
    """The face at subsurface-volume (a replicate per seed, ``spp`` each), moved by ``translate`` mm: eq4_shift's check,
    the TPR of each replicate and of their mean, seconds."""
    from skinrender.evaluation.budget import BUDGET_FRACTION
    from skinrender.model.chromaticity import ncc
    from skinrender.rendering.face.request import face_request
    from skinrender.rendering.face.scene import skin_reflectance_of
    from skinrender.rendering.face.shift import face_budget
    from skinrender.rendering.face.validation import mean_rendering, render_replicates_request, shift_against
    from skinrender.rendering.validation import analytic_reference
    from skinrender.studies.face.ladder import score_frame

    request = face_request("face", CAMERA, 2856, 5900, skin=skin, physics="subsurface-volume", size=size, spp=spp,
                           translate_mm=translate)
    analytic = ncc(analytic_reference(CAMERA, skin_reflectance_of(request.skin)[None], 2856, 5900))[0]
    budget, locus = face_budget(request.camera, analytic, 5900, BUDGET_FRACTION)
    start = time.perf_counter()
    replicated = render_replicates_request(request, seeds)
    seconds = time.perf_counter() - start
    mean = mean_rendering(replicated)
    check = shift_against(replicated, budget, locus, mean.image)
    each = [score_frame(render, locus)[0]["tpr"] for render in replicated.renders]
    return check, np.array(each, dtype=float), score_frame(mean, locus)[0]["tpr"], seconds


def face(argv) -> None:
    size, spp, replicates = 64, 8, 12
    results = {}
    for name, translate, base in (("at its place", None, 0), ("moved +100 mm (x)", (100.0, 0.0, 0.0), 1000)):
        check, each, tpr, seconds = _face_at(translate, [base + k for k in range(replicates)], size, spp)
        results[name] = (check, each, tpr)
        t = stats.t.ppf(0.975, replicates - 1)
        d = check.details
        print(f"the face ({size}×{size} px, {replicates} replicates × {spp} spp), {name}: eq4_shift "
              f"{check.statistic:.4f} (95 % interval {check.statistic - t * d['shift_length_se']:.4f}–"
              f"{check.statistic + t * d['shift_length_se']:.4f}), shift (r, g) "
              f"{' '.join(f'{v:+.4f}' for v in d['shift'])} ± {' '.join(f'{v:.4f}' for v in d['shift_se'])}; TPR "
              f"of the mean image {tpr:.3f}, of a replicate {each.mean():.3f} ± {each.std(ddof=1) / np.sqrt(len(each)):.3f}"
              f"; {seconds:.0f} s, {_load()}", flush=True)
    (a, ea, _), (b, eb, _) = results.values()
    z = (np.array(a.details["shift"]) - np.array(b.details["shift"])) / np.hypot(a.details["shift_se"],
                                                                                 b.details["shift_se"])
    welch = stats.ttest_ind(ea, eb, equal_var=False)
    print(f"moved − at its place: shift (r, g) differs by {' '.join(f'{v:+.2f}' for v in z)} standard errors "
          f"(Šidák 95 % over 2: |z| ≤ {stats.norm.ppf(1 - (1 - 0.95 ** 0.5) / 2):.2f}); a replicate's TPR by "
          f"{eb.mean() - ea.mean():+.4f} (Welch p = {welch.pvalue:.2f})")


def _sphere(spec: str, radius: float, layers: str, spp: int, px: int = 16, seed: int = 1):
    """A sphere of skin of ``radius`` mm under the sky, its top seen straight down over 0.2 mm: its pixels and the
    flat slab's adding-doubling expectation."""
    from skinrender.model.camera import camera
    from skinrender.rendering.face.document import channel_integral
    from skinrender.rendering.renderer import emitter_grid, mitsuba_spectrum as _spectrum
    from skinrender.rendering.skin_integrator import register
    from skinrender.rendering.subsurface import integrator_dict, medium_dict, skin_media_of, slab_reflectance
    from skinrender.rendering.subsurface_chart import _film
    from skinrender.rendering.variants import mitsuba
    from skinrender.spectra import GRID_DEFAULT, planck

    mi = mitsuba("llvm_ad_spectral")
    register(mi)
    grid, cam = GRID_DEFAULT, camera(CAMERA)
    media = skin_media_of(spec, grid)
    epidermis, _ = media.layers
    sky = planck(emitter_grid(grid), 2856.0)
    sky = sky / sky.max()
    t = mi.ScalarTransform4f
    integrator = integrator_dict(media.layers, grid)  # as the face has it: re-anchored near the epidermis
    if layers == "depth from the last contact":
        integrator["reanchor_depth"] = 0.0
    boundary = {"type": "dielectric", "int_ior": 1.4, "ext_ior": 1.0}
    document = {"type": "scene", "integrator": integrator,
                "sensor": {"type": "orthographic", "near_clip": 1e-3, "far_clip": 1e3,
                           "to_world": t().look_at(origin=[0, 0, 10.0], target=[0, 0, 0], up=[0, 1, 0])
                           @ t().scale([0.1, 0.1, 1]),
                           "sampler": {"type": "independent", "sample_count": spp},
                           "film": _film(cam, grid, (0, 1, 2), px)},
                "sky": {"type": "constant", "radiance": _spectrum(emitter_grid(grid), sky)},
                "skin": {"type": "sphere", "center": [0, 0, -radius], "radius": radius, "bsdf": boundary,
                         "interior": medium_dict(epidermis, grid)}}
    if layers == "offset sphere":
        integrator["epidermis_thickness"] = 0.0
        document["junction"] = {"type": "sphere", "center": [0, 0, -radius],
                                "radius": radius - float(epidermis.thickness_mm), "bsdf": {"type": "null"}}
    scene = mi.load_dict(document)
    pixels = np.array(mi.render(scene, seed=seed, spp=spp), dtype=np.float64).reshape(-1, 3)
    lam = emitter_grid(grid)
    expected = channel_integral(cam, grid, lam, np.interp(lam, grid.wavelengths, slab_reflectance(media.layers))
                                * sky)
    return pixels, expected


def curvature(argv) -> None:
    spp = int(argv[0]) if argv else 1024
    ways = ("depth", "depth from the last contact", "offset sphere")
    for name, spec in (("light", "skin-model:melanin=0.02"), ("dark", "skin-model:melanin=0.3")):
        for radius in (2.0, 5.0, 10.0, 20.0, 50.0):
            start = time.perf_counter()
            rows = {}
            for layers in ways:
                pixels, expected = _sphere(spec, radius, layers, spp)
                rows[layers] = (pixels.mean(axis=0), pixels.std(axis=0, ddof=1) / np.sqrt(len(pixels)), expected)
            o, ose, e = rows["offset sphere"]

            def against(way):
                d, dse, _ = rows[way]
                return (f"{' '.join(f'{v:+.4f}' for v in d / o - 1)} ± "
                        f"{' '.join(f'{v:.4f}' for v in np.hypot(dse / o, ose * d / o**2))}")

            print(f"{name} skin, sphere of radius {radius:g} mm (16×16 px × {spp} spp each): layers by depth "
                  f"(re-anchored, the face's) / offset sphere − 1 {against('depth')}; from the last contact alone "
                  f"{against('depth from the last contact')}; offset sphere / flat slab (AD) − 1 "
                  f"{' '.join(f'{v:+.4f}' for v in o / e - 1)} ± {' '.join(f'{v:.4f}' for v in ose / e)}; "
                  f"{time.perf_counter() - start:.0f} s, {_load()}", flush=True)


def chart(argv) -> None:
    spp = argv[0] if argv else "160"
    for camera_, lights in ((CAMERA, ("2856", "2856")), ("Canon EOS 5D Mark II", ("2300", "5900"))):
        command = ["skinrender", "validate", "skin_patches", "--camera", camera_, "--prevailing", lights[0],
                   "--calibration", lights[1], "--physics", "subsurface-volume", "--spp", spp, "--seed", "1",
                   "--tolerance", "0.05", "--max-minutes", "60", "--json"]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        done = subprocess.run([os.path.join(os.path.dirname(sys.executable), "skinrender"), *command[1:]],
                              capture_output=True, text=True)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
        if not done.stdout.strip():
            print(f"{' '.join(command)}: exit {done.returncode}, no JSON: {done.stderr.strip()[-600:]}", flush=True)
            continue
        document = json.loads(done.stdout)
        checks = document["checks"]
        print(f"{' '.join(command[:-1])}: {document['verdict']} (exit {done.returncode}); equivalence "
              f"{checks['equivalence']['verdict']}, bound {document['bound']:.3f}; difference "
              f"{checks['difference']['verdict']} (max |z| {checks['difference'].get('statistic', float('nan')):.2f} / "
              f"critical {checks['difference'].get('threshold', float('nan')):.2f}); largest |relative error| "
              f"{document.get('max_rel_error', float('nan')):.4f}; spp {document['spp']}; {wall:.0f} s "
              f"({cpu:.0f} s CPU), {_load()}", flush=True)


def noise(argv) -> None:
    import skinrender.rendering.face.effects.subsurface as effect
    from skinrender.rendering.face.render import _load as loaded_documents
    from skinrender.studies.face.ladder import ladder

    original = effect.integrator_dict
    for size, spp in ((64, 24), (128, 64), (64, 384)):
        for on in (False, True):
            effect.integrator_dict = lambda *a, **k: {**original(*a, **k), "through": on}  # noqa: B023
            loaded_documents.cache_clear()  # the loaded documents are cached by level, not by integrator
            start = time.perf_counter()
            result = ladder(CAMERA, 2856, 5900, levels=["subsurface-volume"], spp=spp, size=size)
            row = result.document()["levels"][0]
            print(f"ladder's subsurface-volume row at {size} px, {spp} spp, through the boundary {'on' if on else 'off'}: "
                  f"eq4_shift {row['eq4_shift']:.4f} (≤ {row['eq4_shift_bound']:.4f}), TPR {row['tpr']:.3f}; "
                  f"{time.perf_counter() - start:.0f} s, {_load()}", flush=True)
    effect.integrator_dict = original


def main(what: str, argv) -> None:
    {"face": face, "curvature": curvature, "chart": chart, "noise": noise}[what](argv)
