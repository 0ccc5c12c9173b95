"""pdeface.Mesh and reading / writing: numpy views without copies, files equal to the command's."""

import pickle

import numpy as np
import pytest

import pdeface


def test_read_gives_numpy_views_of_the_scan(faces):
    m = pdeface.read(faces / "facefuns_f18.ply")
    assert m.vertices.shape == (30204, 3) and m.vertices.dtype == np.float64
    assert m.faces.shape[1] == 3 and m.faces.dtype == np.int32 and len(m.faces) > 50000
    assert m.faces.min() >= 0 and m.faces.max() < len(m.vertices)
    # Views of the mesh's own storage: the same memory every time, read-only, alive after the mesh's name.
    a, b = m.vertices, m.vertices
    assert np.shares_memory(a, b)
    assert not a.flags.writeable
    with pytest.raises(ValueError):
        a[0, 0] = 1.0
    del m
    assert np.isfinite(a).all()


def test_a_mesh_from_arrays_round_trips_through_every_format(tmp_path):
    v = np.array([[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]], dtype=float)
    f = np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
    m = pdeface.Mesh(v, f, units="mm", name="tetra")
    assert m.units == "mm" and m.name == "tetra" and len(m) == 4 and m.normals is None
    for ext in ["ply", "obj", "off", "stl", "glb", "wrl", "drc"]:
        path = tmp_path / f"t.{ext}"
        pdeface.write(m, path)
        back = pdeface.read(path)
        assert len(back.faces) == 4, ext
        # Draco splits vertices per corner: the same positions, some of them repeated.
        np.testing.assert_allclose(np.unique(back.vertices.round(2), axis=0), np.unique(v, axis=0), atol=2e-3,
                                   err_msg=ext)


def test_a_bad_array_is_a_bad_call():
    with pytest.raises(ValueError, match=r"vertices must be an array of shape \(n, 3\)"):
        pdeface.Mesh(np.zeros((4, 2)))
    with pytest.raises(IndexError, match="refers to vertex 7 of 3"):
        pdeface.Mesh(np.zeros((3, 3)), [[0, 1, 7]])
    with pytest.raises(ValueError, match="finite"):
        pdeface.Mesh([[0, 0, 0], [1, np.nan, 0], [0, 1, 0]], [[0, 1, 2]])
    with pytest.raises(ValueError, match="units"):
        pdeface.Mesh(np.zeros((3, 3)), units="furlong")


def test_meshes_pickle(faces):
    m = pdeface.read(faces / "facefuns_m46.drc")
    back = pickle.loads(pickle.dumps(m))
    np.testing.assert_array_equal(back.vertices, m.vertices)
    np.testing.assert_array_equal(back.faces, m.faces)
    assert back.units == m.units


def test_bytes_equal_the_commands_files(faces, cli, tmp_path):
    scan = faces / "facefuns_f18.ply"
    m = pdeface.read(scan)
    for ext in ["glb", "drc", "ply", "obj"]:
        out = tmp_path / f"f18.{ext}"
        cli("convert", scan, out)
        assert pdeface.to_bytes(m, ext) == out.read_bytes(), ext
        again = pdeface.from_bytes(out.read_bytes(), f"again.{ext}")
        assert len(again.vertices) == len(m.vertices) or ext == "drc"


def test_a_dropped_attribute_is_a_note(tmp_path):
    m = pdeface.Mesh(np.eye(3), [[0, 1, 2]], colors=np.ones((3, 4)))
    with pytest.warns(pdeface.Note, match="colo"):
        pdeface.write(m, tmp_path / "t.stl")
