"""
Mitsuba documents of face scenes
================================

The Mitsuba 3 scene dictionary of a :class:`~skinrender.rendering.face.scene.FaceScene`
at one level of physics, and the spectral pieces every face render shares.
What a level puts in it (the integrator, the skin's and props' materials,
the lights) comes from its effects
(:class:`~skinrender.rendering.face.effects.levels.Level`); this module
places them in the scene.

-   :func:`channel_groups`, :func:`film_dict`: the camera's channels as
    ``specfilm`` passes (as the chart renderer splits them).
-   :func:`light_irradiance`, :func:`channel_integral`: a light's spectral
    irradiance (W·m⁻²·nm⁻¹ from its illuminance) and ``∫ f(λ) x_k(λ) dλ``
    as the renderer integrates it.
-   :func:`transform`: a shape's 4×4 matrix.
-   :func:`face_document`: the scene dictionary.

Modelling choices
-----------------
-   Lights are Planckian, set by illuminance (lx, over the grid's range):
    a point light of irradiance ``E(λ)`` at the camera target (facing it)
    has radiant intensity ``E(λ) d²`` (``d`` its distance to the target); the
    environment is a ``constant`` emitter of radiance ``E(λ) / π``, which a
    surface open to all of it receives as irradiance ``E``. Every spectrum is
    tabulated in float64 every ``grid.step / EMITTER_REFINE`` nm and handed
    to Mitsuba divided by one ``scale`` (the largest irradiance peak),
    restored after rendering, as the chart renderer does. Each emitter is
    sampled in proportion to its illuminance (Mitsuba's ``sampling_weight``):
    with one sample per hit, the key light and its ambient sky chosen alike
    nearly doubled the skin's NCC noise (std 0.0061 under the key alone,
    0.0110 with the sky, 0.0071 weighted; 128 px, 32 spp, measured); the
    expectation is the same.
-   Every surface of the effects of today is ``twosided``
    (:func:`~skinrender.rendering.face.effects.base.twosided`): the scan is
    open at the shoulders, and a path that enters it must meet skin, not a
    black back face.
-   The bundled head becomes a Mitsuba ``Mesh`` built from its arrays; a
    user's mesh file is loaded by Mitsuba's ``obj`` or ``ply`` plugin with
    the same transform. Shading is smooth (interpolated vertex normals)
    unless the scene asks for ``smooth = false`` (each triangle's own
    normal): interpolated shading normals are not energy conserving (the
    white furnace's head reads 0.35 % ± 0.015 % below the sky with them,
    −0.01 % ± 0.007 % flat, measured over 100 × 12 renders), so the white
    furnace is rendered flat.
"""

from __future__ import annotations

import numpy as np

from ...hints import NDArrayFloat
from ...model.camera import Camera
from ...model.exposure import irradiance_planck
from ...spectra import WavelengthGrid
from ..renderer import EMITTER_REFINE, channels_separate, mitsuba_spectrum, channel_names
from ..scene import reflectance_of
from .labels import SHAPE_SKIN, prop_shape_id
from .scene import MESH_HEAD, FaceScene, Light, skin_reflectance_of

__all__ = ["channel_groups", "film_dict", "light_irradiance", "channel_integral", "transform", "face_document",
           "skin_material", "light_documents"]


def channel_groups(cam: Camera, grid: WavelengthGrid, channels: str = "auto") -> list[tuple[int, ...]]:
    """The render passes, as indices into R, G, B (one pass, or one per channel for narrow sensors)."""
    return [(0,), (1,), (2,)] if channels_separate(cam, grid, channels) else [(0, 1, 2)]


def film_dict(cam: Camera | None, grid: WavelengthGrid, group: tuple[int, ...], width: int, height: int,
              channels: dict | None = None) -> dict:
    """
    A float32 ``specfilm``, box filter, with the camera's ``group`` channels (named as for charts), or with
    ``channels`` (name → Mitsuba spectrum: a spectral render's bands, :func:`~skinrender.rendering.bands.film_channels`)
    in their place.
    """
    film = {"type": "specfilm", "width": int(width), "height": int(height), "component_format": "float32",
            "rfilter": {"type": "box"}}
    if channels is not None:
        return {**film, **channels}
    curves, names = cam.sensitivities(grid), channel_names(cam)
    for k in group:
        film[names[k]] = mitsuba_spectrum(grid.wavelengths, curves[k])
    return film


def light_irradiance(light: Light, grid: WavelengthGrid) -> tuple[NDArrayFloat, NDArrayFloat]:
    """
    The wavelengths (nm) of the tabulated emitters and a light's spectral
    irradiance there, W·m⁻²·nm⁻¹: a Planckian of the light's illuminance
    (lx, over the grid's range).
    """
    fine = WavelengthGrid(grid.start, grid.end, grid.step / EMITTER_REFINE)
    return fine.wavelengths, irradiance_planck(light.temperature, light.illuminance, fine)


def channel_integral(cam: Camera, grid: WavelengthGrid, wavelengths: NDArrayFloat,
                     spectrum: NDArrayFloat) -> NDArrayFloat:
    """
    ``∫ f(λ) x_k(λ) dλ`` per channel (trapezoid on ``wavelengths``, the curves
    linearly interpolated from ``grid``): what a ``specfilm`` estimates for a
    pixel of spectral radiance ``f``. Shape ``spectrum.shape[:-1] + (3,)``.
    """
    x = np.array([np.interp(wavelengths, grid.wavelengths, curve) for curve in cam.sensitivities(grid)])
    weights = np.gradient(wavelengths) if wavelengths.size > 1 else np.ones(1)
    weights[[0, -1]] = np.diff(wavelengths)[[0, -1]] / 2
    return (np.asarray(spectrum) * weights) @ x.T


def _rotation(degrees) -> NDArrayFloat:
    """About x, then y, then z (degrees)."""
    out = np.eye(3)
    for axis, angle in enumerate(np.radians(degrees)):
        c, s = np.cos(angle), np.sin(angle)
        i, j = [(1, 2), (2, 0), (0, 1)][axis]
        r = np.eye(3)
        r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
        out = r @ out
    return out


def transform(translate, rotate, scale) -> NDArrayFloat:
    """The 4×4 matrix ``T(translate) · R(rotate) · S(scale)`` (rotations about x, y, z in turn, degrees)."""
    m = np.eye(4)
    m[:3, :3] = _rotation(rotate) * np.broadcast_to(np.asarray(scale, dtype=np.float64), (3,))
    m[:3, 3] = translate
    return m


def _scaled(matrix: NDArrayFloat, unit: float) -> NDArrayFloat:
    """``matrix`` in a scene of ``unit`` scene units per metre (unchanged, not even rounded, at 1)."""
    return matrix if unit == 1.0 else np.diag([unit, unit, unit, 1.0]) @ matrix


def _mesh(mi, scene: FaceScene, material: dict, unit: float = 1.0) -> dict | object:
    """The head: a Mitsuba ``Mesh`` of the bundled scan, or the user's ``obj``/``ply``, with ``material``."""
    matrix = _scaled(transform(scene.mesh_translate, scene.mesh_rotate, scene.mesh_scale), unit)
    if scene.mesh != MESH_HEAD:
        kind = "ply" if scene.mesh.lower().endswith(".ply") else "obj"
        return {"type": kind, "filename": scene.mesh, "to_world": mi.ScalarTransform4f(matrix), **material,
                "face_normals": not scene.mesh_smooth}
    from ...datasets.head import mesh_head

    vertices, triangles = mesh_head()
    positions = vertices.astype(np.float64) @ matrix[:3, :3].T + matrix[:3, 3]
    props = mi.Properties()
    for key, value in material.items():
        props[key] = mi.load_dict(value)
    mesh = mi.Mesh(SHAPE_SKIN, len(vertices), len(triangles), props=props,
                   has_vertex_normals=scene.mesh_smooth)
    params = mi.traverse(mesh)
    # the arrays' own types: mi.Float, or dynamic arrays in scalar variants
    params["vertex_positions"] = type(params["vertex_positions"])(positions.astype(np.float32).ravel())
    params["faces"] = type(params["faces"])(triangles.astype(np.uint32).ravel())
    params.update()
    if scene.mesh_smooth:
        mesh.recompute_vertex_normals()
    return mesh


def face_document(mi, scene: FaceScene, cam: Camera | None, grid: WavelengthGrid, level, skin: str,
                  group: tuple[int, ...], spp: int, seed: int, sampler: str, lights: dict[str, Light],
                  scale: float, channels: dict | None = None) -> dict:
    """
    The Mitsuba scene dictionary of a face scene.

    Parameters
    ----------
    mi
        The ``mitsuba`` module, its (spectral) variant set.
    level
        The :class:`~skinrender.rendering.face.effects.levels.Level`: its effects give the integrator and
        the skin's and props' materials (effects acting after rendering, as ``noise``, add nothing here).
    skin
        The skin spec (:func:`~skinrender.rendering.face.scene.skin_reflectance_of`).
    group
        The camera channels of this pass.
    channels
        A spectral render's film channels (name → Mitsuba spectrum) in place of the camera's (``cam``
        ``None``).
    lights
        The lights to add (the level's, :meth:`~skinrender.rendering.face.effects.levels.Level.lights`),
        with their temperatures: a point light where it has a position, else the uniform environment.
    scale
        Every emitter spectrum is divided by it (W·m⁻²·nm⁻¹): multiply the
        render by it.
    """

    matrix = mi.ScalarTransform4f
    c = scene.camera
    setup = level.setup(scene, cam, grid, lights, skin=skin)
    k = level.scene_scale  # scene units per metre: 1 but with an effect that needs finer ray offsets
    at = _at(k)
    document = {
        "type": "scene",
        "integrator": level.integrator(setup),
        "sensor": {
            "type": "perspective", "fov": c.fov, "fov_axis": "x", "near_clip": 1e-3 * k, "far_clip": 1e3 * k,
            "to_world": matrix().look_at(origin=at(c.position), target=at(c.target), up=list(c.up)),
            "sampler": {"type": sampler, "sample_count": int(spp), "seed": int(seed)},
            "film": film_dict(cam, grid, group, c.width, c.height, channels),
        },
    }
    document[SHAPE_SKIN] = _mesh(mi, scene, skin_material(scene, level, grid, skin, lights, cam), k)
    for index, prop in enumerate(scene.props):
        size = [prop.size[0] / 2, prop.size[1] / 2, prop.size[2] / 2 if prop.shape == "cube" else 1.0]
        document[prop_shape_id(index)] = {
            "type": prop.shape, "to_world": matrix(_scaled(transform(prop.position, prop.rotate, size), k)),
            **level.prop(reflectance_of(prop.reflectance, grid, f"prop {prop.name!r}"), setup),
        }
    return {**document, **light_documents(scene, level, grid, lights, scale)}


def _at(unit: float):
    """A point (m) in a scene of ``unit`` scene units per metre, as a list (unchanged, not even rounded, at 1)."""
    return (lambda point: list(point)) if unit == 1.0 else (lambda point: [unit * v for v in point])


def skin_material(scene: FaceScene, level, grid: WavelengthGrid, skin: str, lights: dict[str, Light],
                  cam: Camera | None = None) -> dict:
    """The skin's shape properties at ``level`` (``{"bsdf": …}``, a medium's ``"interior"``), plain dicts."""
    setup = level.setup(scene, cam, grid, lights, skin=skin)
    return level.skin(skin_reflectance_of(skin, grid, "skin"), setup)


def light_documents(scene: FaceScene, level, grid: WavelengthGrid, lights: dict[str, Light], scale: float) -> dict:
    """
    The emitters of ``lights`` (``{"light_NAME": …}``, plain dicts): a point light where it has a position (its
    intensity giving its irradiance at the camera target, in the level's scene units), else the uniform
    environment; every spectrum divided by ``scale`` (W·m⁻²·nm⁻¹).
    """
    at = _at(level.scene_scale)
    target = np.asarray(at(scene.camera.target))
    out = {}
    for name, light in lights.items():
        lam, irradiance = light_irradiance(light, grid)
        if light.position is None:
            out[f"light_{name}"] = {"type": "constant", "sampling_weight": float(light.illuminance),
                                    "radiance": mitsuba_spectrum(lam, irradiance / np.pi / scale)}
        else:  # the intensity of a point light that gives its irradiance at the target, in scene units
            squared = float(np.sum((np.asarray(at(light.position)) - target) ** 2))
            out[f"light_{name}"] = {"type": "point", "position": at(light.position),
                                    "sampling_weight": float(light.illuminance),
                                    "intensity": mitsuba_spectrum(lam, irradiance * squared / scale)}
    return out
