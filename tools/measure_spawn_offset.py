#!/usr/bin/env python3
"""
The face's skin, mean output (R, G, B) over four seeds, moved X mm along x from the origin
(``docs/subsurface.md``, "Float32's useful range"; ``rendering.placement.SPAWN_OFFSET_MAX_MM``):

    python tools/measure_spawn_offset.py SIZE SPP LEVEL X1,X2,…    # e.g. 16 64 direct 0,1e4,3e4,1e5,3e5,1e6
"""
import sys, numpy as np, skinrender as sr
size = int(sys.argv[1]); spp = int(sys.argv[2]); physics = sys.argv[3]
xs = [float(x) for x in sys.argv[4].split(",")]
for x in xs:
    vals = []
    for seed in range(4):
        r = sr.render("face", "gbell:9@450,540,610", "A", 5900, size=size, spp=spp, seed=seed, physics=physics,
                      translate_mm=(x, 0.0, 0.0))
        skin = r.labels == 1
        vals.append(r.image[skin].mean(axis=0))
    v = np.array(vals); m = v.mean(0); se = v.std(0, ddof=1) / 2
    print(f"x {x:9.3g} mm: skin mean R {m[0]:.2f}±{se[0]:.2f} G {m[1]:.2f}±{se[1]:.2f} B {m[2]:.2f}±{se[2]:.2f}", flush=True)
