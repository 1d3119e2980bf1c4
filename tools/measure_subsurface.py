"""
Measure the choices of the subsurface level (docs/subsurface.md): one flat skin slab of
skinrender.rendering.subsurface_chart rendered under the uniform sky and compared with its adding-doubling
reflectance through a camera, per channel, with its pixel standard deviation and wall time.

    PYTHONPATH=$PWD python tools/measure_subsurface.py integrators   # volpathmis vs volpath, roulette off
    PYTHONPATH=$PWD python tools/measure_subsurface.py roulette      # Mitsuba's roulette (depth 5) vs off
    PYTHONPATH=$PWD python tools/measure_subsurface.py variants      # scalar_spectral vs llvm_ad_spectral
    PYTHONPATH=$PWD python tools/measure_subsurface.py offsets       # the face's one medium away from the origin
    PYTHONPATH=$PWD python tools/measure_subsurface.py effective     # the one medium vs the two layers (diffuse light)
    PYTHONPATH=$PWD python tools/measure_subsurface.py depth         # the dermis' depth (adding-doubling alone)
    PYTHONPATH=$PWD python tools/measure_subsurface.py samplers      # patch means' spread vs their standard errors
    PYTHONPATH=$PWD python tools/measure_subsurface.py calibration   # validate's difference test: false alarms

Each prints one line per setting: the rendered mean over adding-doubling's, minus 1, per channel (R G B), the pixel
standard deviation relative to the mean, the standard error of that ratio, and the seconds of the render.
"""

from __future__ import annotations

import sys
import time

import numpy as np

CAMERA = "gbell:9@450,540,610"
PX = 16


def _world(document: dict, mi, unit_mm: float, offset_mm: float) -> dict:
    """The slab's document moved ``offset_mm`` along x and written in units of ``unit_mm`` mm."""
    t = mi.ScalarTransform4f
    move = t().scale(1.0 / unit_mm) @ t().translate([offset_mm, 0.0, 0.0])
    for key, value in document.items():
        if isinstance(value, dict) and "to_world" in value:
            value["to_world"] = move @ value["to_world"]
        if isinstance(value, dict) and value.get("type") == "homogeneous":
            value["scale"] = float(unit_mm)
    sensor = document["sensor"]
    sensor["to_world"] = move @ sensor["to_world"]
    sensor["near_clip"], sensor["far_clip"] = sensor["near_clip"] / unit_mm, sensor["far_clip"] / unit_mm
    return document


FIT_095 = dict(melanin=0.0374, blood=0.0214, oxygenation=0.767, scattering=72.0, scattering_power=1.24)
"""The skin model fitted to Vrhel's 095 (a patch of skin_patches, its lowest scattering): rounded."""


def slab(melanin: float, spp: int, integrator: str = "volpathmis", rr_depth: int | None = None,
         variant: str = "scalar_spectral", single: bool = False, unit_mm: float = 1.0, offset_mm: float = 0.0,
         seed: int = 1, sampler: str = "multijitter", parameters: dict | None = None, px: int = PX,
         ) -> tuple[np.ndarray, np.ndarray, float]:
    """Rendered mean / adding-doubling − 1 per channel, the pixel std relative to the mean, seconds."""
    from skinrender.datasets.skin_model import SkinParameters, reflectance_of_layers, skin_layers
    from skinrender.model.camera import camera
    from skinrender.rendering.face.document import channel_integral
    from skinrender.rendering.renderer import emitter_grid
    from skinrender.rendering.subsurface import SkinMedia, effective_layer, medium_dict, slab_reflectance
    from skinrender.rendering.subsurface_chart import SLAB_DERMIS_MM, slab_document
    from skinrender.rendering.variants import mitsuba
    from skinrender.spectra import GRID_DEFAULT, planck

    mi = mitsuba(variant)
    grid, cam = GRID_DEFAULT, camera(CAMERA)
    chosen = SkinParameters(**(parameters or {"melanin": melanin}))
    layers = skin_layers(grid.wavelengths, chosen)
    media = SkinMedia(str(chosen), chosen, None, layers, grid.wavelengths)
    sky = planck(emitter_grid(grid), 2856.0)
    sky = sky / sky.max()
    document = slab_document(mi, media, None, cam, grid, (0, 1, 2), px, spp, sampler, sky)
    document["integrator"]["type"] = integrator
    if rr_depth is not None:
        document["integrator"]["rr_depth"] = rr_depth
    reflectance = slab_reflectance(layers)
    if single:  # the face's one effective medium, no junction
        effective = effective_layer(layers)
        document["dermis"] = medium_dict(effective, grid)
        del document["junction"], document["epidermis"]
        document["top"]["interior"] = {"type": "ref", "id": "dermis"}
        from dataclasses import replace

        reflectance = reflectance_of_layers((replace(effective, thickness_mm=SLAB_DERMIS_MM),))
    document = _world(document, mi, unit_mm, offset_mm)
    start = time.perf_counter()
    image = np.array(mi.render(mi.load_dict(document), seed=seed), dtype=np.float64).reshape(-1, 3)
    seconds = time.perf_counter() - start
    lam = emitter_grid(grid)
    expected = channel_integral(cam, grid, lam, np.interp(lam, grid.wavelengths, reflectance) * sky)
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


def _line(label: str, result) -> None:
    error, spread, seconds = result
    print(f"{label:48s} mean/AD-1 {' '.join(f'{v:+.4f}' for v in error)}  pixel std {' '.join(f'{v:.3f}' for v in spread)}"
          f"  SE {' '.join(f'{v / np.sqrt(PX * PX):.4f}' for v in spread)}  {seconds:.1f} s")


def main(what: str) -> None:
    if what == "integrators":
        for integrator in ("volpathmis", "volpath"):
            _line(f"{integrator}, melanin 0.05, 16 spp, roulette off", slab(0.05, 16, integrator))
    elif what == "roulette":
        for rr, label in ((5, "Mitsuba's default (from depth 5)"), (None, "off")):
            _line(f"volpathmis, melanin 0.05, 64 spp, roulette {label}", slab(0.05, 64, rr_depth=rr))
    elif what == "variants":
        for variant in ("scalar_spectral", "llvm_ad_spectral"):
            slab(0.05, 1, variant=variant)  # warm-up (kernels, scene)
            _line(f"{variant}, melanin 0.05, 64 spp", slab(0.05, 64, variant=variant))
    elif what == "offsets":
        for melanin in (0.02, 0.3):
            for unit, offset in ((1.0, 0.0), (1.0, 100.0), (1000.0, 100.0)):
                where = f"{offset:g} mm from the origin, scene unit {unit:g} mm"
                _line(f"one medium, melanin {melanin}, {where}", slab(melanin, 32, single=True, unit_mm=unit,
                                                                      offset_mm=offset))
    elif what == "effective":
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
            runs = [slab(0.0, 16, sampler=sampler, parameters=FIT_095, px=8, seed=seed) for seed in range(150)]
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
