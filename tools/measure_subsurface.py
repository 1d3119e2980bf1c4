"""
Measure the choices of the subsurface level (docs/subsurface.md): one flat skin slab of
skinrender.rendering.subsurface_chart rendered under the uniform sky and compared with its adding-doubling
reflectance through a camera, per channel, with its pixel standard deviation and wall time.

    PYTHONPATH=$PWD python tools/measure_subsurface.py effective     # one effective medium vs the two layers
    PYTHONPATH=$PWD python tools/measure_subsurface.py depth         # the dermis' depth (adding-doubling alone)
    PYTHONPATH=$PWD python tools/measure_subsurface.py samplers      # patch means' spread vs their standard errors
    PYTHONPATH=$PWD python tools/measure_subsurface.py calibration   # validate's difference test: false alarms

The integrator's own measurements (placements, the old integrator, the face, curvature, the chart's time, noise) are
tools/measure_skin_integrator.py's.
"""

from __future__ import annotations

import sys
import time

import numpy as np

CAMERA = "gbell:9@450,540,610"
PX = 16


FIT_095 = dict(melanin=0.0374, blood=0.0214, oxygenation=0.767, scattering=72.0, scattering_power=1.24)
"""The skin model fitted to Vrhel's 095 (a patch of skin_patches, its lowest scattering): rounded."""


def slab(spp: int, seed: int = 1, sampler: str = "multijitter", parameters: dict | None = None, px: int = PX,
         ) -> tuple[np.ndarray, np.ndarray, float]:
    """A slab (skinvolpath): rendered mean / adding-doubling − 1 per channel, the pixel std relative to the mean,
    seconds."""
    from skinrender.datasets.skin_model import SkinParameters, skin_layers
    from skinrender.model.camera import camera
    from skinrender.rendering.face.document import channel_integral
    from skinrender.rendering.renderer import emitter_grid
    from skinrender.rendering.skin_integrator import register
    from skinrender.rendering.subsurface import SkinMedia, slab_reflectance
    from skinrender.rendering.subsurface_chart import slab_document
    from skinrender.rendering.variants import mitsuba
    from skinrender.spectra import GRID_DEFAULT, planck

    mi = mitsuba("llvm_ad_spectral")
    register(mi)
    grid, cam = GRID_DEFAULT, camera(CAMERA)
    chosen = SkinParameters(**(parameters or {}))
    layers = skin_layers(grid.wavelengths, chosen)
    media = SkinMedia(str(chosen), chosen, None, layers, grid.wavelengths)
    sky = planck(emitter_grid(grid), 2856.0)
    sky = sky / sky.max()
    document = slab_document(mi, media, None, cam, grid, (0, 1, 2), px, spp, sampler, sky)
    start = time.perf_counter()
    image = np.array(mi.render(mi.load_dict(document), seed=seed), dtype=np.float64).reshape(-1, 3)
    seconds = time.perf_counter() - start
    lam = emitter_grid(grid)
    expected = channel_integral(cam, grid, lam, np.interp(lam, grid.wavelengths, slab_reflectance(layers)) * sky)
    mean, std = image.mean(axis=0), image.std(axis=0, ddof=1)
    return mean / expected - 1, std / mean, seconds


def _calibration(seeds: int) -> None:
    """validate's difference test (family-wise α 0.01) on a chart of three slabs over many seeds."""
    import tempfile

    from skinrender.evaluation.verdict import binomial_interval
    from skinrender.rendering.validation import validate

    chart = ('name = "three"\ncolumns = 4\npatch_px = 8\ngap_px = 2\n' + "".join(
        f'[[patch]]\nname = "{name}"\nreflectance = "skin-model:{spec}"\nskin = true\n' for name, spec in (
            ("light", "melanin=0.02"), ("095", ",".join(f"{k}={v}" for k, v in FIT_095.items())),
            ("dark", "melanin=0.3"))))
    with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as handle:
        handle.write(chart)
    fails, largest, start = 0, [], time.perf_counter()
    for seed in range(seeds):
        result = validate(handle.name, CAMERA, 2856, 5900, spp=16, seed=2 * seed, sampler="independent",
                          physics="subsurface", tolerance=0.5)
        fails += result.difference.outcome == "fail"
        largest.append(float(np.abs(result.z).max()))
    low, high = binomial_interval(fails, seeds)
    print(f"difference test (α 0.01), 3 slabs at 8 × 8 px, 16 spp, independent sampler: {fails}/{seeds} false "
          f"alarms (95 % interval {low:.3f}–{high:.3f}); largest |z| median {np.median(largest):.2f}, max "
          f"{max(largest):.2f}; {time.perf_counter() - start:.0f} s")


def main(what: str) -> None:
    if what == "effective":
        from skinrender.datasets.skin_model import SkinParameters, reflectance_of_layers, skin_layers
        from skinrender.rendering.subsurface import effective_layer

        lam = np.arange(400.0, 701.0)
        for melanin in (0.02, 0.1, 0.3):
            layers = skin_layers(lam, SkinParameters(melanin=melanin))
            single = effective_layer(layers)
            normal = np.abs(reflectance_of_layers((single,)) - reflectance_of_layers(layers)).max()
            two, one = reflectance_of_layers(layers, diffuse=True), reflectance_of_layers((single,), diffuse=True)
            print(f"melanin {melanin}: normal incidence max |ΔR| {normal:.1e}; diffuse incidence max |ΔR| "
                  f"{np.abs(one - two).max():.4f}, max relative {np.abs(one / two - 1).max():.4f}")
    elif what == "samplers":
        for sampler in ("independent", "multijitter"):
            runs = [slab(16, sampler=sampler, parameters=FIT_095, px=8, seed=seed) for seed in range(150)]
            errors = np.array([r[0] for r in runs])
            se = np.array([r[1] * (1 + r[0]) / 8 for r in runs])  # pixel std over √64, relative to the analytic
            ratio = errors.std(axis=0, ddof=1) / np.sqrt(np.mean(se**2, axis=0))
            print(f"{sampler}: 150 seeds, Vrhel 095's fit, 8 × 8 px, 16 spp: spread of the means over their "
                  f"standard errors {' '.join(f'{v:.2f}' for v in ratio)}; max |z| "
                  f"{np.abs(errors / se).max():.1f}; spread of the means (relative) "
                  f"{' '.join(f'{v:.4f}' for v in errors.std(axis=0, ddof=1))}; mean error "
                  f"{' '.join(f'{v:+.4f}' for v in errors.mean(axis=0))}")
    elif what == "calibration":
        _calibration(100)
    elif what == "depth":
        from skinrender.datasets.skin_model import SkinParameters, reflectance_of_layers, skin_layers
        from skinrender.rendering.subsurface import slab_reflectance

        lam = np.arange(400.0, 701.0, 5.0)
        for melanin in (0.02, 0.05, 0.3):
            layers = skin_layers(lam, SkinParameters(melanin=melanin))
            model = reflectance_of_layers(layers)
            print(f"melanin {melanin}: " + ", ".join(f"{d:g} mm {np.abs(slab_reflectance(layers, d) / model - 1).max():.1e}"
                                                     for d in (2, 3, 4, 5, 8)))
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "")
