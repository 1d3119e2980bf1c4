# ---
# jupyter:
#   jupytext:
#     formats: ipynb,py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#       format_version: '1.3'
#       jupytext_version: 1.19.6
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 06 · A camera, not only its curves: photons, noise and a design that pays for them
#
# ## Overview
# A camera of three spectral curves sees without noise, so both of the paper's criteria reward sensors that crowd together. Here the camera records photons: optics, pixel, exposure, quantum efficiency, shot, dark and read noise, full well, gain and ADC (EMVA 1288's model), at a light level in lux.
#
# **What you will learn**
# - how the simulated camera is measured the way real ones are (photon transfer);
# - that noisy renders agree with the analytic sensor model patch by patch;
# - why the noise-free best detector (560/570/590 nm) fails on noisy pixels, and what a design that pays for noise chooses instead.

# %%
import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
import numpy as np
import skinrender as sr
from skinrender.model.imager import list_imagers
from skinrender.studies.benchmarks.ptc import photon_transfer
from skinrender.rendering.imaging import render_imaged
from skinrender.rendering.sensor_validation import validate_imaged
from skinrender.rendering.validation import analytic_reference
from skinrender.design.bank import sensor_bank, positions_grid
from skinrender.design.noise_aware import noisy_setting, bank_rates, triplet_noisy_rates, TPR_MIN
from skinrender.design.optimise import optimise_camera

CAM = sr.camera('gbell:9@450,540,610')
[(row['name'], row['full_well_e'], row['read_noise_e'], row['bits']) for row in list_imagers()]

# %% [markdown]
# ## Step 1: photon transfer of the simulated camera (EMVA 1288)
# Two frames per exposure of a rendered grey chart; variance against mean gives the gain.

# %%
ptc = photon_transfer(CAM, 'sony-imx174', points=10, spp=8)
means = np.array([p['mean_dn'] for p in ptc['points']]); variances = np.array([p['variance_dn'] for p in ptc['points']])
fig, ax = plt.subplots(figsize=(5, 3.5))
for k, c in enumerate('rgb'): ax.plot(means[:, k], variances[:, k], 'o-', color=c, ms=3)
ax.set(xlabel='mean − dark (DN)', ylabel='temporal variance (DN²)')
{k: ptc[k] for k in ('gain_dn_per_e', 'read_noise_e', 'full_well_e', 'stated')}

# %% [markdown]
# ## Step 2: noisy renders against the analytic sensor model
# The Macbeth chart at 20 lx and 2000 lx (auto exposure, at most a 1/30 s frame).

# %%
chart = sr.load_scene('macbeth')
ratio = analytic_reference(CAM, chart.reflectances(sr.GRID_DEFAULT), 2856.0, 2856.0) / 255.0
fig, axes = plt.subplots(1, 2, figsize=(9, 3.2))
for ax, lux in zip(axes, (20.0, 2000.0)):
    imaged = render_imaged(chart, CAM, 2856.0, 2856.0, 'sony-imx174', lux, spp=16, seed=1)
    check = validate_imaged(imaged, ratio)
    ax.imshow(np.clip(imaged.rendering.image / 255.0, 0, 1) ** (1 / 2.2)); ax.axis('off')
    ax.set_title(f'{lux:g} lx, {imaged.exposure_s * 1e3:.1f} ms, noise model: {check.difference.reason}')

# %% [markdown]
# ## Step 3: detection against the light level
# The noise-free best triplet (560/570/590 nm) against a spread one (450/540/610 nm).

# %%
where = positions_grid('400:700:10')
banks = [sensor_bank(9, sr.reflectances(n).on(sr.GRID_DEFAULT), where) for n in ('skin', 'munsell')]
rows = []
for lux in (20.0, 200.0, 2000.0, 20000.0):
    setting = noisy_setting('sony-imx174', lux, samples=2)
    rates = [bank_rates(b, setting, 9) for b in banks]
    for name, triplet in (('560 570 590', [16, 17, 19]), ('450 540 610', [5, 14, 21])):
        tpr, fpr = triplet_noisy_rates(*banks, *rates, triplet, setting)
        rows.append((lux, name, round(tpr, 3), round(fpr, 3)))
rows

# %% [markdown]
# ## Step 4: a design that pays for noise
# Nelder–Mead on the noisy criterion (TPR kept ≥ 0.9, FPR minimised), a short run.

# %%
skin, munsell = (sr.reflectances(n).on(sr.GRID_DEFAULT) for n in ('skin', 'munsell'))
noisy = optimise_camera('detection', skin, munsell, [[450, 540, 610]], max_evaluations=8,
                        noisy=noisy_setting('sony-imx174', 500.0, samples=2))
free = optimise_camera('detection', skin, munsell, [[450, 540, 610]], max_evaluations=8)
{'noise-free design': free.peaks.round(1).tolist(), 'noise-aware design': noisy.peaks.round(1).tolist()}

# %% [markdown]
# ## Reference API
# `skinrender.model.imager`, `model.exposure`, `model.noise`, `rendering.imaging`, `studies.benchmarks.ptc`, `design.noise_aware`; commands `imagers`, `ptc`, `score`, and `--imager` on `render`, `validate`, `detect`, `search`, `design`. The docs' noise page (`docs/imager.md`) gives the full-size measurements.
