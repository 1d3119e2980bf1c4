#!/usr/bin/env python3
"""
A GPU machine's check of Mitsuba's variants: cuda_ad_spectral, llvm_ad_spectral and scalar_spectral on the Macbeth
chart through gbell:9 (2856 K → 5900 K): render seconds (first call, then warm at 64 and 1024 spp), Eq. 4's
validation at 1024 spp (verdict, bound, largest relative error), and a 256 px face at 64 spp.

    PYTHONPATH=. python tools/gpu_check.py cuda_ad_spectral llvm_ad_spectral scalar_spectral

Writes ``$OUT/gpu.json`` (or ./gpu.json) and prints a line per variant. ``FACE`` names another face scene (the
bundled one's Munsell prop needs luxpy). Figures: docs/speed.md, "On a GPU".
"""
import json, os, sys, time
import mitsuba as mi
import skinrender as sr
from skinrender.rendering.loaded import release_scenes

out = {"mitsuba": mi.__version__, "variants": mi.variants()}
kw = dict(camera="gbell:9@450,540,610", prevailing=2856, calibration=5900)
for variant in sys.argv[1:]:
    row = {}
    try:
        t = time.perf_counter(); sr.render("macbeth", spp=64, seed=1, variant=variant, **kw); row["first_64spp_s"] = time.perf_counter() - t
        for spp in (64, 1024):
            t = time.perf_counter(); r = sr.render("macbeth", spp=spp, seed=2, variant=variant, **kw)
            row[f"warm_{spp}spp_s"] = time.perf_counter() - t
        row["variant_used"] = r.variant
        t = time.perf_counter(); v = sr.validate("macbeth", spp=1024, seed=3, variant=variant, **kw)
        row["validate_1024spp_s"] = time.perf_counter() - t
        row["verdict"] = v.verdict.outcome if v.verdict is not None else None
        row["bound"] = v.bound
        row["max_rel_error"] = float(abs(v.rel_error).max())
        t = time.perf_counter(); f = sr.render(os.environ.get("FACE", "face"), spp=64, seed=1, variant=variant, size=256, **kw)
        row["face_256px_64spp_first_s"] = time.perf_counter() - t
        t = time.perf_counter(); f = sr.render(os.environ.get("FACE", "face"), spp=64, seed=2, variant=variant, size=256, **kw)
        row["face_256px_64spp_warm_s"] = time.perf_counter() - t
    except Exception as e:  # report, go on with the next variant
        row["error"] = f"{type(e).__name__}: {e}"[:400]
    release_scenes()
    out[variant] = row
    print(variant, json.dumps(row), flush=True)
path = os.path.join(os.environ.get("OUT", "."), "gpu.json")
with open(path, "w") as handle:
    json.dump(out, handle, indent=1)
