#!/usr/bin/env python3
"""
Issue 34's GPU check: the skin's two levels, ``subsurface`` (adding-doubling's slab as a BSDF) and
``subsurface-volume`` (the project's skinvolpath), timed in ``cuda_ad_spectral`` and, on the same machine,
``llvm_ad_spectral`` — the default ladder, each skin level alone on the face at the ladder's defaults (128 px,
64 spp), and the volumetric chart of 30 skins at ``--tolerance 0.05`` and 512 spp. Each ladder runs twice in a row
for a variant (the first compiles Dr.Jit's kernels; the second finds them cached), the chart once, as a user would
run them, and each command's whole-process wall seconds are recorded with what it found.

    PYTHONPATH=. python tools/gpu_subsurface.py cuda_ad_spectral llvm_ad_spectral

Writes ``$OUT/gpu_subsurface.json`` (or ./gpu_subsurface.json) and prints a line per run. A run that passes
``LIMIT_S`` (default 150 s) is stopped and recorded as such. Figures: docs/subsurface.md, "On a GPU".
"""
import json
import os
import signal
import subprocess
import sys
import time

CAMERA = ["--camera", "gbell:9@450,540,610"]
LADDER = ["ladder", *CAMERA, "--prevailing", "2200", "--calibration", "5900", "--json"]
CHART = ["validate", "skin_patches", *CAMERA, "--prevailing", "2856", "--calibration", "2856", "--spp", "512",
         "--seed", "1", "--tolerance", "0.05", "--max-minutes", "60", "--json"]
RUNS = {
    "ladder_default": LADDER,
    "ladder_subsurface": [*LADDER, "--levels", "subsurface"],
    "ladder_subsurface_volume": [*LADDER, "--levels", "subsurface-volume", "--max-minutes", "120"],
    "chart_subsurface_volume": [*CHART, "--physics", "subsurface-volume"],
}
LIMIT_S = float(os.environ.get("LIMIT_S", "150"))
ONLY = [name for name in os.environ.get("ONLY", "").split(",") if name]
"""``ONLY=ladder_subsurface_volume`` runs those of :data:`RUNS` alone; ``SPP=768`` gives the ladders that spp."""
if os.environ.get("SPP"):
    RUNS = {name: [*args, "--spp", os.environ["SPP"]] if name.startswith("ladder") else args
            for name, args in RUNS.items()}


def summary(name: str, document: dict) -> dict:
    """What a run found: per level its seconds, Eq. 4 shift and TPR change; a chart's verdict and bound."""
    if name.startswith("ladder"):
        return {"verdict": document.get("verdict"), "levels": [
            {"name": level.get("name", level.get("level")), "seconds": level.get("seconds"),
             "variant": level.get("variant"), "spp": level.get("spp"), "eq4_shift": level.get("eq4_shift"),
             "eq4_shift_bound": level.get("eq4_shift_bound"),
             "tpr_change": (level.get("detection") or {}).get("tpr_change")} for level in document["levels"]]}
    keep = ("verdict", "exit_status", "bound", "max_rel_error", "spp", "variant", "elapsed_s")
    return {key: document.get(key) for key in keep if key in document}


def main(variants: list[str]) -> None:
    out = {"argv": sys.argv, "runs": []}
    for variant in variants:
        for name, args in RUNS.items():
            if ONLY and name not in ONLY:
                continue
            for attempt in ("first", "second")[:1 if name.startswith("chart") else 2]:
                command = [sys.executable, "-m", "skinrender", *args, "--variant", variant]
                start = time.perf_counter()
                process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                           start_new_session=True)  # its own group: a stop ends its workers too
                try:
                    stdout, stderr = process.communicate(timeout=LIMIT_S)
                except subprocess.TimeoutExpired:
                    os.killpg(process.pid, signal.SIGKILL)
                    process.communicate()
                    row = {"variant": variant, "run": name, "attempt": attempt, "stopped_after_s": LIMIT_S}
                else:
                    row = {"variant": variant, "run": name, "attempt": attempt,
                           "wall_s": time.perf_counter() - start, "rc": process.returncode}
                    try:
                        row.update(summary(name, json.loads(stdout)))
                    except (ValueError, KeyError) as error:
                        row["error"] = f"{error}: {stdout[-300:]} {stderr[-600:]}"
                out["runs"].append(row)
                print(json.dumps(row), flush=True)
                with open(os.path.join(os.environ.get("OUT", "."), "gpu_subsurface.json"), "w") as handle:
                    json.dump(out, handle, indent=1)  # after every run: a stopped session keeps what it measured
                if "stopped_after_s" in row:
                    break


if __name__ == "__main__":
    main(sys.argv[1:])
