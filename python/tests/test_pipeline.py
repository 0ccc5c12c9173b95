"""The method from Python gives the command's bytes, and lets other Python threads run meanwhile."""

import threading
import time

import numpy as np
import pytest

import pdeface


@pytest.fixture(scope="module")
def f18(faces):
    return pdeface.read(faces / "facefuns_f18.ply")


def test_encode_and_decode_give_the_commands_files(faces, f18, cli, tmp_path):
    data = pdeface.encode(f18, ratio=0.10)
    cli("encode", faces / "facefuns_f18.ply", "-o", tmp_path / "f18.pdef", "--ratio", "0.1")
    assert data == (tmp_path / "f18.pdef").read_bytes()
    assert 800 < len(data) < 1100
    face = pdeface.decode(data, resolution=200)
    cli("decode", tmp_path / "f18.pdef", "-o", tmp_path / "f18.ply", "--resolution", "200")
    assert pdeface.to_bytes(face, "ply") == (tmp_path / "f18.ply").read_bytes()
    assert face.normals is not None


def test_a_residual_layer_within_its_size_and_every_prefix_decodes(faces, f18, cli, tmp_path):
    data = pdeface.encode(f18, size=4096)
    cli("encode", faces / "facefuns_f18.ply", "-o", tmp_path / "f18.pdef", "--size", "4096")
    assert data == (tmp_path / "f18.pdef").read_bytes()
    assert 3000 < len(data) <= 4096
    curves_only = len(pdeface.encode(f18))
    full = pdeface.decode(data, resolution=100)
    part = pdeface.decode(data[: (curves_only + len(data)) // 2], resolution=100)
    assert full.vertices.shape == part.vertices.shape
    assert not np.array_equal(full.vertices, part.vertices)
    with pytest.raises(ValueError, match="not both"):
        pdeface.encode(f18, size=4096, target_error=0.05)


def test_a_texture_layer_gives_the_commands_file_and_a_textured_mesh(faces, cli, tmp_path):
    james = pdeface.read(faces / "james.obj")
    data = pdeface.encode(james, texture=True, texel=1.0)
    cli("encode", faces / "james.obj", "-o", tmp_path / "james.pdef", "--texture", "--texel", "1")
    assert data == (tmp_path / "james.pdef").read_bytes()
    assert 8000 < len(data) < 20000
    face = pdeface.decode(data, resolution=100)
    assert face.texcoords is not None and face.texcoords.shape == (face.vertices.shape[0], 2)
    with pytest.raises(ValueError, match="texture_quality"):
        pdeface.encode(james, texture=True, texture_quality=0)


def test_reconstruct_gives_the_commands_mesh(faces, f18, cli, tmp_path):
    mesh = pdeface.reconstruct(f18, ratio=0.2)
    cli("reconstruct", faces / "facefuns_f18.ply", "-o", tmp_path / "r.ply", "--ratio", "0.2")
    assert pdeface.to_bytes(mesh, "ply") == (tmp_path / "r.ply").read_bytes()


def test_alignment_and_profiles(f18):
    a = pdeface.align(f18)
    assert 0.35 <= a.confidence <= 1 and a.scale == pytest.approx(1.0, rel=0.3)
    nose = a.landmarks["nose_tip"]
    np.testing.assert_allclose(a.to_canonical(nose[None, :]), [[0, 0, 0]], atol=1e-6)
    np.testing.assert_allclose(a.to_scan(a.to_canonical(f18.vertices[:10])), f18.vertices[:10], atol=1e-9)
    assert set(pdeface.detect_landmarks(f18)) >= {"nose_tip", "eye_inner_left", "mouth_right"}
    doc = pdeface.profiles(f18, ratio=0.1, landmarks=a.landmarks)
    assert len(doc["curves"]) == 28


def test_a_result_that_fails_its_self_check_is_refused(f18):
    # Four curves cannot hold a face: the surface between them is centimetres off the scan.
    with pytest.raises(pdeface.SelfCheckError, match="self-check failed"):
        pdeface.reconstruct(f18, curves=4)
    with pytest.raises(pdeface.SelfCheckError):
        pdeface.encode(f18, curves=4)
    with pytest.warns(pdeface.Note, match="self-check failed"):
        mesh = pdeface.reconstruct(f18, curves=4, force=True)
    assert len(mesh.vertices) > 0


def test_given_landmarks_are_used(f18):
    a = pdeface.align(f18)
    again = pdeface.align(f18, landmarks=a.landmarks)
    assert again.confidence is None
    np.testing.assert_allclose(again.landmarks["nose_tip"], a.landmarks["nose_tip"], atol=1e-9)
    np.testing.assert_allclose(again.rotation, a.rotation, atol=1e-3)


def test_long_calls_release_the_gil(f18):
    ticks = 0
    done = threading.Event()

    def encode():
        pdeface.encode(f18, ratio=0.1)
        done.set()

    t = threading.Thread(target=encode)
    start = time.monotonic()
    t.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    t.join()
    elapsed = time.monotonic() - start
    # Holding the GIL, the encode would stop this loop for its whole duration (hundreds of ms).
    assert elapsed > 0.05
    assert ticks > 0.3 * elapsed / 0.0011
