"""Tests for :mod:`skinrender.datasets.head`: the bundled head mesh, its checksum, licence and rebuild."""

from __future__ import annotations

import hashlib
import importlib.util

import numpy as np
import pytest

from skinrender.datasets import head
from skinrender.datasets.registry import ROOT_RESOURCES
from skinrender.errors import SkinrenderError

from ..conftest import ROOT_REPOSITORY


class TestMeshHead:
    def test_checksum_and_size(self):
        data = (ROOT_RESOURCES / head.FILE_HEAD).read_bytes()
        assert hashlib.sha256(data).hexdigest() == head.SHA256_HEAD
        assert len(data) < 1_000_000

    def test_triangles(self):
        vertices, triangles = head.mesh_head()
        assert vertices.shape == (8844, 3) and vertices.dtype == np.float32
        assert triangles.shape == (head.TRIANGLES_HEAD, 3) == (17684, 3) and triangles.dtype == np.int32
        assert triangles.min() == 0 and triangles.max() == len(vertices) - 1
        assert not vertices.flags.writeable and not triangles.flags.writeable

    def test_geometry(self):
        """About metres, y up, the face (its nose tip, the largest z) looking along +z, wound outwards."""
        vertices, triangles = head.mesh_head()
        extent = vertices.max(axis=0) - vertices.min(axis=0)
        assert 0.4 < extent[0] < 0.5 and 0.35 < extent[1] < 0.5
        nose = vertices[np.argmax(vertices[:, 2])]
        assert abs(nose[0]) < 0.01
        a, b, c = (vertices[triangles[:, k]].astype(np.float64) for k in range(3))
        assert np.einsum("ij,ij->i", a, np.cross(b, c)).sum() > 0  # positive signed volume: normals outwards

    def test_licence_beside_it(self):
        text = (ROOT_RESOURCES / head.FILE_HEAD_LICENCE).read_text(encoding="utf-8")
        assert "Lee Perry-Smith" in text and "Creative Commons Attribution 3.0" in text
        assert "CC BY 3.0" in head.LICENCE_HEAD and "Lee Perry-Smith" in head.SOURCE_HEAD

    def test_a_modified_file_is_refused(self, tmp_path, monkeypatch):
        (tmp_path / head.FILE_HEAD).write_bytes((ROOT_RESOURCES / head.FILE_HEAD).read_bytes() + b"\0")
        monkeypatch.setattr(head, "ROOT_RESOURCES", tmp_path)
        head.mesh_head.cache_clear()
        try:
            with pytest.raises(SkinrenderError, match="SHA-256"):
                head.mesh_head()
        finally:
            head.mesh_head.cache_clear()


def test_the_tool_rebuilds_the_same_bytes(shared_data, tmp_path, monkeypatch):
    """tools/build_head_mesh.py turns the distributed OBJ into the bundled npz, byte for byte."""
    path = ROOT_REPOSITORY / "tools" / "build_head_mesh.py"
    spec = importlib.util.spec_from_file_location("build_head_mesh", path)
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    monkeypatch.setattr(tool, "ROOT_RESOURCES", tmp_path)
    assert tool.main(["build_head_mesh.py", str(shared_data / "head_lee_perry_smith.obj")]) == 0
    assert (tmp_path / head.FILE_HEAD).read_bytes() == (ROOT_RESOURCES / head.FILE_HEAD).read_bytes()
    licence = head.FILE_HEAD_LICENCE
    assert (tmp_path / licence).read_bytes() == (ROOT_RESOURCES / licence).read_bytes()
