#!/usr/bin/env python3
"""
Rebuild the head mesh that skinrender bundles from the Lee Perry-Smith OBJ.

    python tools/build_head_mesh.py [PATH/head_lee_perry_smith.obj]

(default: ``../shared/data/head_lee_perry_smith.obj`` beside the checkout).

Writes, under ``skinrender/datasets/resources/``:

- ``head_lee_perry_smith.npz``: ``vertices`` (8 844 × 3, float32, the OBJ's
  units, about metres: y up, the face looking along +z) and ``triangles``
  (17 684 × 3, int32, 0-based; each OBJ quad a b c d split into a b c and
  a c d, keeping its winding). UVs, the material and the texture maps are
  left out: skinrender gives the whole head one reflectance.
- ``head_lee_perry_smith_LICENSE.txt``: the attribution and licence text,
  copied as distributed (CC BY 3.0).

The npz is written byte for byte the same on every run (fixed zip
timestamps), and the script prints its SHA-256, to paste into
``skinrender/datasets/head.py``.

Source: "Infinite, 3D Head Scan" by Lee Perry-Smith (Infinite Realities,
based on a work at triplegangers.com), as distributed by Morgan McGuire's
Computer Graphics Archive (https://casual-effects.com/data), CC BY 3.0.
"""

from __future__ import annotations

import hashlib
import io
import shutil
import sys
import zipfile
from pathlib import Path

import numpy as np

ROOT_REPOSITORY = Path(__file__).resolve().parents[1]
ROOT_RESOURCES = ROOT_REPOSITORY / "skinrender" / "datasets" / "resources"
DEFAULT_OBJ = ROOT_REPOSITORY.parent / "shared" / "data" / "head_lee_perry_smith.obj"
SHA256_OBJ = "762544f36d38048ac1ea6ff3f2438171d516d32c44d126756664d0fccbbe1553"
NAME = "head_lee_perry_smith"
ZIP_DATE = (1980, 1, 1, 0, 0, 0)


def read_obj(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Vertices ``(n, 3)`` and triangles ``(m, 3)``, 0-based, of an OBJ (polygons split into fans)."""
    vertices, triangles = [], []
    for line in path.read_text(encoding="utf-8", errors="replace").splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            corners = [int(token.split("/")[0]) for token in parts[1:]]
            # OBJ indices are 1-based, or negative: relative to the end
            corners = [c - 1 if c > 0 else len(vertices) + c for c in corners]
            triangles += [[corners[0], corners[k], corners[k + 1]] for k in range(1, len(corners) - 1)]
    return np.array(vertices, dtype=np.float32), np.array(triangles, dtype=np.int32)


def write_npz(path: Path, arrays: dict[str, np.ndarray]) -> None:
    """An ``.npz`` (deflated) whose bytes depend only on the arrays."""
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for name, array in arrays.items():
            buffer = io.BytesIO()
            np.lib.format.write_array(buffer, np.ascontiguousarray(array), allow_pickle=False)
            info = zipfile.ZipInfo(f"{name}.npy", date_time=ZIP_DATE)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            archive.writestr(info, buffer.getvalue(), compresslevel=9)


def main(argv: list[str]) -> int:
    source = Path(argv[1]) if len(argv) > 1 else DEFAULT_OBJ
    if not source.exists():
        print(f"{source}: not found (give the OBJ's path)", file=sys.stderr)
        return 2
    digest = hashlib.sha256(source.read_bytes()).hexdigest()
    if digest != SHA256_OBJ:
        print(f"{source}: SHA-256 {digest}, expected {SHA256_OBJ} (another version of the scan?)",
              file=sys.stderr)
        return 2
    vertices, triangles = read_obj(source)
    assert triangles.min() >= 0 and triangles.max() < len(vertices)
    target = ROOT_RESOURCES / f"{NAME}.npz"
    write_npz(target, {"vertices": vertices, "triangles": triangles})
    shutil.copyfile(source.with_name(f"{NAME}_LICENSE.txt"), ROOT_RESOURCES / f"{NAME}_LICENSE.txt")
    print(f"{target.name}: {len(vertices)} vertices, {len(triangles)} triangles, "
          f"{target.stat().st_size} bytes")
    print(f"{target.name}: {hashlib.sha256(target.read_bytes()).hexdigest()}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
