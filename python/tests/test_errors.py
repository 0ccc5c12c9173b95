"""Bad input from Python: the command's message and location, as a pdeface.Error subclass; nothing left."""

import os
import pickle

import numpy as np
import pytest

import pdeface
from pdeface import _pdeface
from pdeface.errors import _CLASSES


def test_every_error_code_has_its_class():
    assert set(_pdeface._error_codes()) == set(_CLASSES)


def test_a_missing_file_is_a_file_error(tmp_path):
    missing = tmp_path / "nope.ply"
    with pytest.raises(pdeface.FileError) as e:
        pdeface.read(missing)
    assert isinstance(e.value, OSError) and e.value.source == str(missing)
    assert str(missing) in str(e.value)


def test_a_malformed_file_names_its_line_as_the_command_does(tmp_path, cli):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    with pytest.raises(pdeface.FormatError) as e:
        pdeface.read(bad)
    assert e.value.code == "index out of range" and e.value.line == 4
    shown = cli("info", bad, check=False)
    assert shown.returncode == 1
    assert f"pdeface: error: {e.value}" in shown.stderr


def test_bytes_name_their_offset():
    with pytest.raises(pdeface.FormatError) as e:
        pdeface.decode(b"PDEF\x02" + b"\x00" * 7)
    assert e.value.byte is not None and e.value.source == "<bytes>.pdef"
    assert pickle.loads(pickle.dumps(e.value)).byte == e.value.byte


def test_no_face_in_a_ball():
    theta, phi = np.meshgrid(np.linspace(0.1, 3.0, 40), np.linspace(0, 2 * np.pi, 80))
    ball = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], -1)
    with pytest.raises(pdeface.NoFaceError, match="no face"):
        pdeface.detect_landmarks(pdeface.Mesh(80 * ball.reshape(-1, 3)), source="ball")


def test_a_write_that_fails_leaves_nothing(tmp_path):
    m = pdeface.Mesh(np.eye(3), [[0, 1, 2]])
    with pytest.raises(pdeface.FileError):
        pdeface.write(m, tmp_path / "missing" / "t.ply")
    assert not (tmp_path / "missing").exists()
    with pytest.raises(pdeface.UnsupportedError):
        pdeface.write(m, tmp_path / "t.xyz")
    assert os.listdir(tmp_path) == []


def test_a_bad_option_is_a_value_error(faces):
    m = pdeface.read(faces / "ict_02.glb")
    with pytest.raises(ValueError, match="ratio"):
        pdeface.encode(m, ratio=0.9)
    with pytest.raises(ValueError, match="scheme"):
        pdeface.reconstruct(m, scheme="cubic")
    with pytest.raises(ValueError):
        pdeface.compare([faces / "ict_02.glb"], draco_bits=[40])
