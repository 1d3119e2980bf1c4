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
# # 01 · Stage 1: the set of Planckian illuminants
#
# ## Overview
# The paper's first stage sees Planckian radiators from 2000 K to 10000 K (every 100 K) through a camera (Eq. 1 on a white object), turns them into NCC chromaticities (Eq. 2) and picks ten illuminants equally spaced in the Euclidean measure of the (g, b) pair (Eq. 3). This notebook redraws the paper's Fig. 2 for the cameras skinrender bundles.
#
# **What you will learn**
# - why neither T nor 1/T spaces illuminants evenly in a camera's chromaticity;
# - what Stage 1 selects for real measured cameras, beside the paper's list (2000, 2200, 2500, 2800, 3300, 3900, 4800, 5900, 7500, 10000 K).

# %%
import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
import numpy as np
import skinrender as sr

CAMERAS = [row['name'] for row in sr.list_cameras()]
temperatures = np.arange(2000.0, 10001.0, 100.0)  # K
tracks = {name: sr.illuminant_track(name, temperatures) for name in CAMERAS}
CAMERAS

# %% [markdown]
# ## Step 1: NCC against T and against 1/T (Fig. 2, upper row)
# Each colour is a camera; solid r, dashed g, dotted b.

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
for k, (name, track) in enumerate(tracks.items()):
    for channel, style in zip(range(3), ['-', '--', ':']):
        label = name if channel == 0 else None
        axes[0].plot(track.temperatures, track.chromaticities[:, channel], style, color=f'C{k}', label=label)
        axes[1].plot(1e6 / track.temperatures, track.chromaticities[:, channel], style, color=f'C{k}')
axes[0].set(xlabel='colour temperature T (K)', ylabel='NCC r, g, b')
axes[1].set(xlabel='inverse temperature 10⁶/T (MK⁻¹)', ylabel='NCC r, g, b')
axes[0].legend(fontsize=7)
fig.tight_layout()


# %% [markdown]
# Neither relation is linear: the paper's example, the change between 9000 K and 10000 K against the same change in 1/T from 2000 K, reads as follows for each camera.

# %%
def step(name, t0, t1):
    c = sr.illuminant_track(name, np.array([t0, t1])).chromaticities
    d = np.abs(np.diff(c, axis=0))[0]
    return d[0], d[2], np.hypot(d[0], d[2])

t_same_inverse = 1 / (1 / 2000 - (1 / 9000 - 1 / 10000))
print(f'{"camera":24s} {"9000→10000 K (r, b, both)":34s} {"2000→%.0f K" % t_same_inverse:>26s}')
for name in CAMERAS:
    a, b = step(name, 9000, 10000), step(name, 2000, t_same_inverse)
    print(f'{name:24s} ' + ' '.join(f'{v:.4f}' for v in a) + '          ' + ' '.join(f'{v:.4f}' for v in b))

# %% [markdown]
# ## Step 2: b against r, and the measure of Eq. 3 (Fig. 2, lower row)

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
for k, (name, track) in enumerate(tracks.items()):
    axes[0].plot(track.chromaticities[:, 0], track.chromaticities[:, 2], color=f'C{k}', label=name)
    for pair, style in zip(['gb', 'rg', 'rb'], ['-', '--', ':']):
        axes[1].plot(track.temperatures, sr.measure(track.chromaticities, pair), style, color=f'C{k}')
axes[0].set(xlabel='NCC r', ylabel='NCC b')
axes[1].set(xlabel='colour temperature T (K)', ylabel='measure m (solid gb, dashed rg, dotted rb)')
axes[0].legend(fontsize=7)
fig.tight_layout()

# %% [markdown]
# ## Step 3: the Stage 1 selection
# Ten targets equally spaced between the measures at 2000 K and 10000 K; each takes the candidate temperature (100 K grid) whose measure is nearest.

# %%
paper = np.array(sr.TEMPERATURES_PAPER)
print(f'{"paper (Sony DXC-755P)":24s}', ' '.join(f'{t:5.0f}' for t in paper))
for name in CAMERAS:
    selection = sr.illuminant_selection(name)
    print(f'{name:24s}', ' '.join(f'{t:5.0f}' for t in selection.temperatures))

# %%
fig, ax = plt.subplots(figsize=(6, 4))
for k, name in enumerate(CAMERAS):
    selection = sr.illuminant_selection(name)
    ax.plot(selection.track.temperatures, selection.track.measures, color=f'C{k}', label=name)
    ax.plot(selection.temperatures, selection.measures, 'o', color=f'C{k}')
ax.set(xlabel='colour temperature T (K)', ylabel='measure m (NCC g, b)', xscale='log')
ax.legend(fontsize=7)
fig.tight_layout()

# %% [markdown]
# ## What the figures say
# - The chromaticity track is strongly non-linear in T and still non-linear in 1/T, as the paper found; the (g, b) measure grows strictly with T for every bundled camera, so Stage 1 is well posed.
# - The selected sets crowd the low temperatures, like the paper's list. They differ between cameras by a few hundred kelvin in the middle of the range: the set is a property of the camera, which is why `--illuminants auto` exists.
#
# ## Reference API
# `sr.illuminant_track`, `sr.illuminant_selection`, `sr.select_illuminants`, `sr.measure`, `sr.ncc`.
#
# ## References
# The paper (Martinkauppi & Finlayson, CIC 2004; `docs/references.md`), Stage 1 and Fig. 2; Darrodi et al. 2015 (Nikon, Sigma); AMPAS rawtoaces (Canon); Psychtoolbox-3 (Kodak DCS-200).
