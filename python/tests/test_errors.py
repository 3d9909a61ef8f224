"""Errors reach Python as symembed's exception types with the library's messages: for a config,
the message `symembed run` prints for the same --set."""

import numpy as np
import pytest
import symembed
from conftest import run_binary, write_config

TRIANGLE_V = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
TRIANGLE_F = np.array([[0, 1, 2]])


def binary_error(binary, tmp_path, pair, setting):
    """The message `symembed run CONFIG --set setting` ends with."""
    config = write_config(tmp_path / "c.yaml", pair.root, {})
    done = run_binary(binary, "run", config, "--set", setting, "--out", tmp_path / "out",
                      "--cache", "", "--quiet", check=False)
    assert done.returncode == 1, done.stderr
    prefix = "symembed run: error: "
    assert done.stderr.startswith(prefix), done.stderr
    return done.stderr[len(prefix):].strip()


@pytest.mark.parametrize("key, value, setting", [
    ("pipeline.sampling.count", "many", "pipeline.sampling.count=many"),
    ("pipeline.flip.type", "coin", "pipeline.flip.type=coin"),
    ("pipeline.sampling.count", -3, "pipeline.sampling.count=-3"),
    ("pipeline.sampling.colour", 1, "pipeline.sampling.colour=1"),
])
def test_config_errors_carry_the_binary_message(binary, tmp_path, pair, key, value, setting):
    with pytest.raises(symembed.ConfigError) as raised:
        symembed.match(TRIANGLE_V, TRIANGLE_F, TRIANGLE_V, TRIANGLE_F, {key: value})
    assert str(raised.value) == binary_error(binary, tmp_path, pair, setting)
    assert isinstance(raised.value, ValueError) and isinstance(raised.value, symembed.Error)


def test_a_missing_config_file_is_an_io_error(tmp_path):
    missing = tmp_path / "missing.yaml"
    with pytest.raises(symembed.IoError, match="cannot open config file") as raised:
        symembed.Shape(TRIANGLE_V, TRIANGLE_F, missing)
    assert isinstance(raised.value, OSError)
    with pytest.raises(symembed.IoError, match="cannot open config file"):
        symembed.run(missing, tmp_path / "out")


def test_arrays_that_are_not_a_mesh_are_refused():
    with pytest.raises(symembed.InvalidInputError, match=r"FA: face 0 has vertex id 3, outside \[0, 3\)"):
        symembed.match(TRIANGLE_V, TRIANGLE_F + 1, TRIANGLE_V, TRIANGLE_F)
    with pytest.raises(symembed.InvalidInputError, match=r"V: expected an array of shape \(n, 3\), got shape \(3, 2\)"):
        symembed.Shape(TRIANGLE_V[:, :2], TRIANGLE_F)
    with pytest.raises(TypeError, match="F: expected integer vertex ids, got dtype float64"):
        symembed.Shape(TRIANGLE_V, TRIANGLE_F.astype(float))


def test_a_mesh_the_pipeline_rejects_raises_the_binary_message(binary, tmp_path, pair):
    # One triangle: the binary records the failure of the shape with its mesh's path.
    root = tmp_path / "data"
    (root / "shapes").mkdir(parents=True)
    (root / "corres").mkdir()
    for name in ("t1", "t2"):
        (root / "shapes" / f"{name}.off").write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
        (root / "corres" / f"{name}.vts").write_text("1\n2\n3\n")
    (root / "test_pairs.txt").write_text("t1 t2\n")
    config = write_config(tmp_path / "t.yaml", root, {})
    out = tmp_path / "out"
    run_binary(binary, "run", config, "--out", out, "--cache", "", "--quiet", "--no-report",
               check=False)
    failures = (out / "base" / "failures.csv").read_text()
    with pytest.raises(symembed.Error) as raised:
        symembed.Shape(TRIANGLE_V, TRIANGLE_F)
    assert str(raised.value)
    assert str(raised.value) in failures.replace('""', '"'), (str(raised.value), failures)
