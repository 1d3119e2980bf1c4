"""
Tests for :mod:`skinrender.rendering.face`: where the analytic model holds on a face, exactly.

Four analytic limits, each rendered small (48 × 48 or less, a few spp) and replicated with
independent seeds: every per-pixel statistic is compared with its analytic value against its own
measured noise (the jackknife over the replicates, Student's t with K − 1 degrees of freedom), the
critical value Šidák-corrected for the number of pixels and channels tested, so that a correct
renderer fails a test with probability :data:`ALPHA` at most.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy import stats

from skinrender.errors import SkinrenderError
from skinrender.model.camera import camera
from skinrender.model.chromaticity import ncc
from skinrender.rendering.exr import read_exr
from skinrender.rendering.face import render_face, white_references, write_face_exr
from skinrender.rendering.face_dict import channel_groups, channel_integral, film_dict, light_irradiance
from skinrender.rendering.face_labels import LABEL_SKIN, interior
from skinrender.rendering.face_scene import Light, load_face_scene, skin_reflectance_of
from skinrender.rendering.validation import FLOAT32_FLOOR, analytic_reference
from skinrender.spectra import GRID_DEFAULT, planck

pytest.importorskip("mitsuba")

CAMERA = "gbell:9@450,540,610"
SIZE = 48
"""Image side, pixels: ~350 interior skin pixels."""
REPLICATES = 12
"""Independent renders (seeds) per test: the jackknife's t has 11 degrees of freedom."""
ALPHA = 0.01
"""Family-wise false-alarm rate of each test (Šidák-corrected over its pixels and channels)."""
SKIN = "skin:089 skin -- caucasian (light)"
LINEAR = 0.05
"""Pixels whose channels' relative standard error is below this are 'lit': a ratio's (NCC's) jackknife
error is then first order, its neglected bias ~LINEAR² of the value, far below the error itself."""


def critical_t(tests: int, replicates: int = REPLICATES, alpha: float = ALPHA) -> float:
    """Two-sided Student-t critical value of ``tests`` independent tests at family-wise ``alpha`` (Šidák)."""
    each = -np.expm1(np.log1p(-alpha) / tests)
    return float(stats.t.isf(each / 2, replicates - 1))


def jackknife(samples: np.ndarray, statistic) -> tuple[np.ndarray, np.ndarray]:
    """``statistic`` of the replicate mean and its jackknife standard error; replicates on axis 0."""
    k = samples.shape[0]
    total = samples.sum(axis=0)
    value = statistic(total / k)
    leave_out = np.array([statistic((total - s) / (k - 1)) for s in samples])
    error = np.sqrt((k - 1) / k * np.sum((leave_out - leave_out.mean(axis=0)) ** 2, axis=0))
    return value, error


def replicates(seed0: int = 0, **kwargs) -> tuple[list, np.ndarray]:
    """``REPLICATES`` renders with consecutive seeds; their balanced images, shape ``(K, h, w, 3)``."""
    renders = [render_face(CAMERA, seed=seed0 + k, **kwargs) for k in range(REPLICATES)]
    return renders, np.array([r.image for r in renders], dtype=np.float64)


def rg(rgb: np.ndarray) -> np.ndarray:
    return ncc(rgb)[..., :2]


class TestShadingCancels:
    def test_every_lit_skin_pixel_has_the_ncc_of_eq4(self):
        """
        Direct light from one Planckian: a skin pixel's radiance is ``ρ(λ) E(λ) G`` with ``G`` the
        shading (cosine, distance, shadowing, the pixel's coverage) independent of λ, so its channels
        are ``G ∫ ρ E x_k`` and its NCC is Eq. 4's, whatever ``G``.
        """
        renders, images = replicates(size=SIZE, spp=16, skin=SKIN, prevailing=2856, calibration=5900)
        labels = renders[0].labels
        mean = images.mean(axis=0)
        error = images.std(axis=0, ddof=1) / np.sqrt(REPLICATES)
        lit = interior(labels, LABEL_SKIN) & np.all(error < LINEAR * mean, axis=-1)
        assert lit.sum() > 100, lit.sum()
        shading = mean[lit].sum(axis=-1)
        assert shading.max() > 3 * shading.min(), "the tested pixels' shading varies more than threefold"
        rho = skin_reflectance_of(SKIN)
        expected = rg(analytic_reference(CAMERA, rho[None], 2856, 5900))[0]
        value, se = jackknife(images[:, lit], rg)
        tests = value.size + 2
        deviation = np.abs(value - expected)
        tolerance = critical_t(tests) * np.hypot(se, FLOAT32_FLOOR * value)
        assert np.all(deviation <= tolerance), (deviation / tolerance).max()
        # pooled over the pixels: a bias too small for any one pixel, in one direction, shows here
        pooled, pooled_se = jackknife(images[:, lit], lambda m: rg(m).mean(axis=0))
        deviation = np.abs(pooled - expected)
        assert np.all(deviation <= critical_t(tests) * np.hypot(pooled_se, FLOAT32_FLOOR)), \
            deviation / pooled_se


class TestWhiteFurnace:
    def test_a_white_head_in_a_uniform_sky_returns_the_sky(self):
        """
        A head of reflectance 1 (both sides) inside a uniform environment of radiance ``L``: the
        radiance leaving every surface is ``L`` (it is the fixed point of ``L_o = ∫ ρ/π L_i cos``
        with ``ρ = 1`` and ``L_i = L`` from every direction), so with every bounce every pixel, the
        concavities included, reads ``∫ L x_k dλ``.
        """
        sky = Light(temperature=5000.0, illuminance=500.0)
        scene = replace(load_face_scene("face"), props=(), key=None, fill=None, environment=sky)
        renders = [render_face(CAMERA, scene, skin="perfect", physics="interreflection", size=32, spp=16,
                               seed=k) for k in range(REPLICATES)]
        radiance = np.array([r.radiance for r in renders])
        lam, irradiance = light_irradiance(sky, GRID_DEFAULT)
        expected = channel_integral(camera(CAMERA), GRID_DEFAULT, lam, irradiance / np.pi)
        head = renders[0].labels == LABEL_SKIN
        assert head.sum() > 100
        mean = radiance.mean(axis=0)
        error = radiance.std(axis=0, ddof=1) / np.sqrt(REPLICATES)
        tests = mean.size + 3
        deviation = np.abs(mean - expected)
        tolerance = critical_t(tests) * np.hypot(error, FLOAT32_FLOOR * expected)
        assert np.all(deviation <= tolerance), (deviation / tolerance).max()
        pooled = radiance[:, head].mean(axis=1)  # the head's mean, per replicate
        error = pooled.std(axis=0, ddof=1) / np.sqrt(REPLICATES)
        deviation = np.abs(pooled.mean(axis=0) - expected)
        tolerance = critical_t(tests) * np.hypot(error, FLOAT32_FLOOR * expected)
        assert np.all(deviation <= tolerance), deviation / error
        # balanced to the sky's own temperature, a white reads 255 everywhere
        assert np.allclose(renders[0].gain * expected, 255.0)


def sphere_emission() -> tuple[np.ndarray, np.ndarray]:
    """Wavelengths (nm) and the relative emission of the sphere: a 3000 K Planckian, peak 1."""
    lam = light_irradiance(Light(3000.0, 1.0), GRID_DEFAULT)[0]
    return lam, planck(lam, 3000.0) / planck(lam, 3000.0).max()


def sphere_channels(rho: np.ndarray, depth: int, seeds, spp: int = 16, size: int = 16) -> np.ndarray:
    """Mean channels of a closed emitting Lambertian sphere rendered from its centre, one row per seed."""
    from skinrender.rendering.renderer import _spectrum
    from skinrender.rendering.variants import choose_variant, mitsuba

    mi = mitsuba(choose_variant())
    cam = camera(CAMERA)
    lam, emission = sphere_emission()
    out = np.zeros((len(seeds), 3))
    for group in channel_groups(cam, GRID_DEFAULT):
        scene = mi.load_dict({
            "type": "scene", "integrator": {"type": "path", "max_depth": depth},
            "sensor": {"type": "perspective", "fov": 60,
                       "sampler": {"type": "independent", "sample_count": spp},
                       "film": film_dict(cam, GRID_DEFAULT, group, size, size)},
            "sphere": {"type": "sphere", "radius": 1.0, "flip_normals": True,
                       "emitter": {"type": "area", "radiance": _spectrum(lam, emission)},
                       "bsdf": {"type": "diffuse", "reflectance": _spectrum(GRID_DEFAULT.wavelengths, rho)}},
        })
        for row, seed in enumerate(seeds):
            image = np.array(mi.render(scene, seed=seed), dtype=np.float64)
            out[row, list(group)] = image.reshape(-1, len(group)).mean(axis=0)
    return out


class TestClosedSphere:
    def test_interreflection_in_a_closed_sphere_saturates_colour(self):
        """
        A closed Lambertian sphere of reflectance ρ(λ) emitting E(λ) uniformly, seen from inside. By
        symmetry the radiance L(λ) is the same at every point and in every direction, and leaves each
        point as emission plus reflection of the uniform incident field:
        ``L = E + (ρ/π) ∫ L cos θ dω = E + ρ L``, so ``L = E / (1 − ρ)`` (every bounce: E Σ ρⁿ),
        whereas one bounce gives ``E (1 + ρ)``. The higher terms ρⁿ are ever more coloured: the
        chromaticity moves further from the light's.
        """
        rho = skin_reflectance_of(SKIN)
        cam = camera(CAMERA)
        results = {}
        for depth, truncated in ((-1, None), (2, 2)):
            samples = sphere_channels(rho, depth, range(REPLICATES))
            lam, emission = sphere_emission()
            rho_fine = np.interp(lam, GRID_DEFAULT.wavelengths, rho)
            radiance = emission / (1 - rho_fine) if truncated is None else emission * (1 + rho_fine)
            expected = rg(channel_integral(cam, GRID_DEFAULT, lam, radiance))
            value, se = jackknife(samples, rg)
            tolerance = critical_t(2 * 2) * np.hypot(se, FLOAT32_FLOOR)
            assert np.all(np.abs(value - expected) <= tolerance), (np.abs(value - expected) / tolerance).max()
            light = rg(channel_integral(cam, GRID_DEFAULT, lam, emission))
            results[depth] = jackknife(samples, lambda m: np.linalg.norm(rg(m) - light, axis=-1))
        (full, se_full), (one, se_one) = results[-1], results[2]
        assert full - one > critical_t(1) * np.hypot(se_full, se_one), (full, one)


class TestDichromatic:
    def test_sheen_lies_in_the_plane_of_body_and_light_colour(self):
        """
        Shafer's dichromatic model: a coated (roughplastic) surface under one light reflects
        ``m_b(geometry) ρ(λ) E(λ) + m_s(geometry) F E(λ)`` with a spectrally flat Fresnel term (one
        refractive index), so each pixel's channels are a non-negative mix of the body colour
        ``∫ ρ E x_k`` and the light's colour ``∫ E x_k``: at zero distance from their plane.
        """
        renders, images = replicates(size=SIZE, spp=16, skin=SKIN, physics="sheen", prevailing=2856,
                                     calibration=2856)
        labels = renders[0].labels
        cam = camera(CAMERA)
        scene = renders[0].scene
        lam, irradiance = light_irradiance(scene.key, GRID_DEFAULT)
        rho = np.interp(lam, GRID_DEFAULT.wavelengths, skin_reflectance_of(SKIN))
        body = renders[0].gain * channel_integral(cam, GRID_DEFAULT, lam, rho * irradiance)
        light = renders[0].gain * channel_integral(cam, GRID_DEFAULT, lam, irradiance)
        normal = np.cross(body, light)
        normal /= np.linalg.norm(normal)
        skin = interior(labels, LABEL_SKIN)
        pixels = images[:, skin]
        distance = pixels @ normal
        mean = distance.mean(axis=0)
        error = distance.std(axis=0, ddof=1) / np.sqrt(REPLICATES)
        scale = np.linalg.norm(pixels.mean(axis=0), axis=-1)
        tests = mean.size + 1
        tolerance = critical_t(tests) * np.hypot(error, FLOAT32_FLOOR * scale)
        assert np.all(np.abs(mean) <= tolerance), (np.abs(mean) / tolerance).max()
        pooled = distance.mean(axis=1)  # over the pixels, per replicate
        error = pooled.std(ddof=1) / np.sqrt(REPLICATES)
        assert abs(pooled.mean()) <= critical_t(tests) * np.hypot(error, FLOAT32_FLOOR * scale.mean())
        # and the highlights are there: some pixels carry the light's colour well beyond their noise
        basis = np.linalg.pinv(np.stack([body, light], axis=1))  # (2, 3): channels -> (m_b, m_s)
        specular = pixels @ basis[1]
        spread = specular.std(axis=0, ddof=1) / np.sqrt(REPLICATES)
        lit = spread > 0  # shadowed pixels are exactly black
        significance = specular.mean(axis=0)[lit] / spread[lit]
        assert significance.max() > critical_t(tests)


class TestLabels:
    def test_skin_props_and_background_are_labelled(self, tmp_path):
        result = render_face(CAMERA, size=SIZE, spp=4)
        names = result.label_names
        assert names["background"] == 0 and names["skin"] == 1
        assert list(names.values()) == list(range(len(names)))
        counts = np.bincount(result.labels.ravel(), minlength=len(names))
        assert np.all(counts > 0), dict(zip(names, counts))
        assert result.spp == 4 and result.physics == "direct" and result.skin == result.scene.skin
        path, png = write_face_exr(tmp_path / "face.exr", result)
        back = read_exr(path, (*result.channels, "label"))
        assert np.array_equal(back[..., 3], result.labels) and png.exists()
        assert np.allclose(back[..., :3], result.image)

    def test_the_scalar_variant_labels_alike(self):
        """The scalar fallback builds the mesh and casts the label rays one by one: the same labels."""
        scalar = render_face(CAMERA, size=12, spp=1, variant="scalar_spectral")
        vectorised = render_face(CAMERA, size=12, spp=1)
        assert scalar.variant == "scalar_spectral" and np.array_equal(scalar.labels, vectorised.labels)

    def test_white_at_the_target_reads_255(self):
        scene = load_face_scene("face")
        white_p, white_c = white_references(scene, camera(CAMERA), scene.key.temperature)
        result = render_face(CAMERA, size=8, spp=1)
        assert np.allclose(result.gain * white_p, 255.0)


class TestRefusals:
    @pytest.mark.parametrize("kwargs, match", [
        ({"physics": "glossy"}, "physics"),
        ({"physics": "direct+sheen"}, "direct"),
        ({"skin": "skin:nobody"}, "skin"),
        ({"skin": "skin-model:melanin=-1"}, "melanin"),
        ({"skin": "skin-model:hair=1"}, "hair"),
        ({"prevailing": "nonsense.csv"}, "prevailing|nonsense"),
        ({"spp": 0}, "spp"),
        ({"seed": -1}, "seed"),
        ({"size": 0}, "size"),
        ({"sampler": "sobol"}, "sampler"),
    ])
    def test_bad_arguments_are_named(self, kwargs, match):
        with pytest.raises(SkinrenderError, match=match):
            render_face(CAMERA, **{"size": 8, "spp": 1, **kwargs})

    def test_mixed_needs_a_second_light(self):
        scene = replace(load_face_scene("face"), fill=None, environment=None)
        with pytest.raises(SkinrenderError, match="mixed"):
            render_face(CAMERA, scene, physics="mixed", size=8, spp=1)
