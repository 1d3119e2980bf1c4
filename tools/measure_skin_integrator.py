"""
Measure the subsurface level's integrator (skinvolpath, skinrender.rendering.skin_integrator) for docs/subsurface.md.

    PYTHONPATH=$PWD python tools/measure_skin_integrator.py placements  # slabs at 0/100/200 mm and tilted vs AD
    PYTHONPATH=$PWD python tools/measure_skin_integrator.py before      # the same with volpathmis (the old level)
    PYTHONPATH=$PWD python tools/measure_skin_integrator.py face        # the face at 0 and +100 mm: eq4_shift, TPR
    PYTHONPATH=$PWD python tools/measure_skin_integrator.py curvature   # spheres: layers by depth vs offset surface
    PYTHONPATH=$PWD python tools/measure_skin_integrator.py through     # a slab under a point light: with, without
    PYTHONPATH=$PWD python tools/measure_skin_integrator.py roulette    # the walk's roulette threshold
    PYTHONPATH=$PWD python tools/measure_skin_integrator.py chart [SPP] # validate skin_patches at --tolerance 0.05
    PYTHONPATH=$PWD python tools/measure_skin_integrator.py noise       # the face's noise at the ladder's spp

Every line says what was rendered and how long it took (wall and CPU seconds, and the load average: the machine is
shared). A slab's value is its mean over its pixels against the adding-doubling reflectance (Eq. 4's white balance
needs no more: the sky is the same in both), relative error per channel (R G B) with its standard error; the
difference test is Šidák's over the three channels at family-wise α 0.01 (normal quantiles: the pixel counts are in
the thousands).
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np
from scipy.stats import norm

CAMERA = "gbell:9@450,540,610"
ALPHA = 0.01
SKINS = {"light": "skin-model:melanin=0.02", "dark": "skin-model:melanin=0.3"}
AD_QUAD_PTS = 64
"""Adding-doubling's quadrature points for the reference: at the package's 16 these slabs' reflectance is 0.05–0.11 %
high (against 128 points; 32: 0.01 %, 64: 0.001 %), a third of the standard error asked of the renders."""


def _load() -> str:
    return "load " + " ".join(f"{v:.1f}" for v in os.getloadavg())


def _critical(values: int, alpha: float = ALPHA) -> float:
    """The two-sided Šidák critical |z| of ``values`` tests at family-wise ``alpha``."""
    return float(norm.ppf(1 - (1 - (1 - alpha) ** (1 / values)) / 2))


def _slab(spec: str, spp: int, px: int, place, integrator: str = "skinvolpath", seed: int = 1, through=None,
          point_light=None, rr=None):
    """A slab of ``spec`` placed by ``place`` (a function of the mitsuba module giving a ScalarTransform4f):
    its pixels (n, 3), the adding-doubling expectation per channel, wall and CPU seconds."""
    from skinrender.datasets.skin_model import reflectance_of_layers
    from skinrender.model.camera import camera
    from skinrender.rendering.face.document import channel_integral
    from skinrender.rendering.renderer import emitter_grid, mitsuba_spectrum as _spectrum
    from skinrender.rendering.skin_integrator import register
    from skinrender.rendering.subsurface import medium_dict, skin_media_of, slab_layers
    from skinrender.rendering.subsurface_chart import slab_document
    from skinrender.rendering.variants import mitsuba
    from skinrender.spectra import GRID_DEFAULT, planck

    mi = mitsuba("scalar_spectral" if integrator == "volpathmis" else "llvm_ad_spectral")
    if integrator != "volpathmis":
        register(mi)
    grid, cam = GRID_DEFAULT, camera(CAMERA)
    media = skin_media_of(spec, grid)
    sky = planck(emitter_grid(grid), 2856.0)
    sky = sky / sky.max()
    t = mi.ScalarTransform4f
    to_world = place(t)
    document = slab_document(mi, media, None, cam, grid, (0, 1, 2), px, spp, "independent", sky, to_world)
    if integrator == "volpathmis":  # the old level: Mitsuba's media, the layers' boundary an offset surface
        epidermis, dermis = media.layers
        document["epidermis"], document["dermis"] = medium_dict(epidermis, grid), medium_dict(dermis, grid)
        document["integrator"] = {"type": "volpathmis", "max_depth": 2**16, "rr_depth": 2**16}
        document["top"]["interior"] = {"type": "ref", "id": "epidermis"}
        document["bottom"]["interior"] = {"type": "ref", "id": "dermis"}
        document["junction"] = {"type": "rectangle", "bsdf": {"type": "null"},
                                "to_world": to_world @ t().translate([0, 0, -epidermis.thickness_mm])
                                @ t().scale([1000.0, 1000.0, 1.0]),
                                "interior": {"type": "ref", "id": "dermis"},
                                "exterior": {"type": "ref", "id": "epidermis"}}
    if through is not None:
        document["integrator"]["through"] = through
    if rr is not None:
        document["integrator"]["rr_weight"] = rr
    if point_light is not None:  # a lamp 100 mm away at ``point_light`` degrees from the normal; the sky off
        del document["sky"]
        angle = np.radians(point_light)
        document["lamp"] = {"type": "point", "position": list(to_world @ mi.ScalarPoint3f(0, 100 * np.sin(angle),
                                                                                         100 * np.cos(angle))),
                            "intensity": _spectrum(emitter_grid(grid), sky * 1e4)}
        for key in ("top", "bottom"):
            document[key]["bsdf"] = {"type": "roughdielectric", "distribution": "ggx", "alpha": 0.35,
                                     "int_ior": 1.4, "ext_ior": 1.0}
    scene = mi.load_dict(document)
    np.array(mi.render(scene, seed=seed + 10**6, spp=1))  # compile first: the time is the render's
    wall, cpu = time.perf_counter(), time.process_time()
    pixels = np.array(mi.render(scene, seed=seed, spp=spp), dtype=np.float64).reshape(-1, 3)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    lam = emitter_grid(grid)
    reflectance = reflectance_of_layers(slab_layers(media.layers), quad_pts=AD_QUAD_PTS)
    expected = channel_integral(cam, grid, lam, np.interp(lam, grid.wavelengths, reflectance) * sky)
    return pixels, expected, wall, cpu


def _summary(pixels, expected) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    mean, sd = pixels.mean(axis=0), pixels.std(axis=0, ddof=1)
    se = sd / np.sqrt(len(pixels)) / expected
    error = mean / expected - 1
    return error, se, sd / mean


PLACEMENTS = {
    "at the origin": lambda t: t(),
    "100 mm away": lambda t: t().translate([100.0, 0.0, 0.0]),
    "200 mm away": lambda t: t().translate([0.0, 200.0, 0.0]),
    "tilted 45°, 100 mm away": lambda t: t().translate([60.0, 0.0, 80.0]) @ t().rotate([1.0, 1.0, 0.0], 45.0),
}


SPP_PLACEMENTS = {"light": 2048, "dark": 3072}
"""The placements' spp: a standard error of 0.3 % or less in every channel (the dark skin's red needs the most)."""


def placements(integrator: str = "skinvolpath", spp: int | None = None, px: int = 16) -> None:
    critical = _critical(3)
    seed = 100
    for name, spec in SKINS.items():
        for where, place in PLACEMENTS.items():
            spp_used = spp or SPP_PLACEMENTS[name]
            seed += 1  # every slab its own samples
            pixels, expected, wall, cpu = _slab(spec, spp_used, px, place, integrator, seed=seed)
            error, se, _ = _summary(pixels, expected)
            z = np.abs(error) / se
            verdict = "pass" if z.max() <= critical else "FAIL"
            print(f"{integrator}, {name} skin ({spec}), {where}, {px}×{px} px × {spp_used} spp, seed {seed}: rendered/AD − 1 "
                  f"{' '.join(f'{v:+.4f}' for v in error)}, SE {' '.join(f'{v:.4f}' for v in se)}; difference "
                  f"test max |z| {z.max():.2f} vs {critical:.2f}: {verdict}; {wall:.1f} s ({cpu:.1f} s CPU), "
                  f"{_load()}", flush=True)


def through() -> None:
    """A rough slab under a point light: the walk's own way to the light alone, and with the connections through
    the boundary (same mean, the spread per path and the largest pixel against the mean)."""
    for name, spec in SKINS.items():
        for on in (False, True):
            pixels, _, wall, cpu = _slab(spec, 256, 32, PLACEMENTS["at the origin"], through=on, point_light=30.0)
            mean, sd = pixels.mean(axis=0), pixels.std(axis=0, ddof=1)
            print(f"{name} skin, rough boundary (GGX 0.35), a point light 30° off the normal, 32×32 px × 256 spp, "
                  f"through the boundary {'on' if on else 'off'}: mean {' '.join(f'{v:.4f}' for v in mean)} "
                  f"± {' '.join(f'{v:.4f}' for v in sd / np.sqrt(len(pixels)))}; per-path spread "
                  f"{' '.join(f'{v:.2f}' for v in sd / mean * np.sqrt(256))}; largest pixel / mean "
                  f"{' '.join(f'{v:.1f}' for v in pixels.max(axis=0) / mean)}; {wall:.1f} s ({cpu:.1f} s CPU), "
                  f"{len(pixels) * 256 / cpu:.0f} paths per CPU second; {_load()}", flush=True)


def roulette() -> None:
    """The walk's roulette threshold: paths per CPU second over the per-path variance (higher is better)."""
    for name, spec in SKINS.items():
        for rr in (0.1, 0.3, 0.6, 0.9):
            pixels, expected, wall, cpu = _slab(spec, 256, 16, PLACEMENTS["at the origin"], rr=rr, seed=5)
            _, _, spread = _summary(pixels, expected)
            per_path = spread * np.sqrt(256)
            rate = len(pixels) * 256 / cpu
            print(f"{name} skin, roulette below {rr:g}: per-path spread {' '.join(f'{v:.2f}' for v in per_path)}, "
                  f"{rate:.0f} paths per CPU second, efficiency {rate / np.mean(per_path**2):.0f}; {_load()}",
                  flush=True)


def main(what: str) -> None:
    if what == "placements":
        placements()
    elif what == "before":
        placements("volpathmis", spp=64)
    elif what == "through":
        through()
    elif what == "roulette":
        roulette()
    elif what in ("face", "curvature", "chart", "noise"):
        from measure_skin_scenes import main as scenes

        scenes(what, sys.argv[2:])
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    main(sys.argv[1] if len(sys.argv) > 1 else "")
