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
# # 07 · A real face under real light
#
# ## Overview
# Flat charts under one light agree with Eq. 4 by construction. A scanned head does not have to: it is shaded, concave, glossy, lit by more than one light and recorded with noise. This notebook renders it at each level of physics and asks what each does to skin detection.
#
# **What you will learn**
# - that shading cancels in NCC (the `direct` level matches Eq. 4 pixel by pixel);
# - which effects move the skin's chromaticity and the detection rates, and by how much;
# - how a skin locus built from rendered faces sits beside the analytic one.

# %%
import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
import numpy as np
import skinrender as sr
from skinrender.rendering.face import render_face
from skinrender.studies.face.ladder import ladder
from skinrender.studies.face.locus import face_locus

CAM = sr.camera('gbell:9@450,540,610')

# %% [markdown]
# ## Step 1: the face and its labels

# %%
face = render_face(CAM, 'face', 2856.0, 5900.0, None, 'sheen', spp=16, size=96)
fig, axes = plt.subplots(1, 2, figsize=(8, 4))
axes[0].imshow(np.clip(face.image / 255.0, 0, 1) ** (1 / 2.2)); axes[0].set_title('sheen, 2856 K → 5900 K')
axes[1].imshow(face.labels, cmap='tab10'); axes[1].set_title('labels')
for ax in axes: ax.axis('off')
face.label_names

# %% [markdown]
# ## Step 2: the ladder of physics
# TPR: lit skin pixels inside the analytic skin locus; FPR: prop pixels inside it. Every default level runs, as
# `skinrender ladder` does: `subsurface` is the fast transport (the skin model's flat slab as a table of angular
# reflectance); its volumetric reference, `subsurface-volume` (skin path traced through its layers), takes minutes
# even at this size and is not a default level: name it in `levels` to run it.

# %%
from skinrender.rendering.face.effects.levels import LEVELS_LADDER

result = ladder(CAM, 2856.0, 5900.0, levels=LEVELS_LADDER, spp=16, size=64, imager='sony-imx174', illuminance=500.0)
[(row['name'], np.round(row['skin_ncc_mean'], 3).tolist(), round(row['tpr'], 3), round(row['fpr'], 3))
 for row in result.levels]

# %% [markdown]
# The ladder's figure (`skinrender ladder … --plot PNG` draws the same): per level the render (the balanced camera RGB shown as sRGB), the label mask, the detected mask (scored pixels inside the analytic skin locus) and the skin pixels' NCC (r, g) over the locus, the props' pixels in blue.

# %%
import tempfile
from pathlib import Path
from IPython.display import Image

Image(filename=str(result.figure(Path(tempfile.mkdtemp()) / 'ladder.png')), width=700)

# %% [markdown]
# ## Step 3: skin loci of rendered faces
# Two skin tones under two lights, tiny renders: the direct level lies on the analytic locus; mixed light moves it.

# %%
fig, ax = plt.subplots(figsize=(5, 4.5))
for physics, colour in (('direct', 'tab:blue'), ('mixed', 'tab:red')):
    loc = face_locus(CAM, pairs=((2856.0, 5900.0), (5900.0, 5900.0)),
                     skins=('skin-model:melanin=0.02', 'skin-model:melanin=0.2'),
                     physics=physics, size=32, spp=16)
    poly = np.array(loc['rendered_polygon'] + loc['rendered_polygon'][:1])
    ax.plot(*poly.T, color=colour, label=f"rendered, {physics} (IoU {loc['overlap_iou']:.2f})")
analytic = np.array(loc['analytic_polygon'] + loc['analytic_polygon'][:1])
ax.plot(*analytic.T, 'k--', label='analytic')
ax.set(xlabel='NCC r', ylabel='NCC g'); ax.legend(fontsize=7)

# %% [markdown]
# ## Reference API
# `skinrender.rendering.face` (`render_face`), `rendering.face.scene`, `studies.face.ladder`, `studies.face.locus`; commands `render face --physics … --skin …`, `detect face` (`--figure`: the detected skin over the face), `ladder` (`--plot`: the figure above); `studies.figures` (`figure_ladder`, `figure_face`, `figure_chart`). The docs' face page (`docs/face.md`) gives the full-size measurements.
