"""Shared fixtures: the symembed binary under test and a synthetic pair with the binary's run of
it, made once per session in a temporary folder (no data outside the test is read).

SYMEMBED_BINARY names the binary (ctest sets it; PYTHONPATH names the built module).
"""

import os
import subprocess
import types

import numpy as np
import pytest

# Per-shape samples of the tests' pipeline: fewer than the default, so that a shape takes about
# a second; every other option is at its default.
PAIR_OPTIONS = {"pipeline.sampling.count": 150}


def read_off(path):
    """An OFF file's (V, F) with numpy: (n, 3) float64 positions, (m, 3) int64 ids."""
    with open(path) as f:
        tokens = f.read().split()
    assert tokens[0] == "OFF", path
    n, m = int(tokens[1]), int(tokens[2])
    V = np.array(tokens[4 : 4 + 3 * n], dtype=np.float64).reshape(n, 3)
    faces = np.array(tokens[4 + 3 * n :], dtype=np.int64).reshape(m, 4)
    assert (faces[:, 0] == 3).all(), path
    return V, faces[:, 1:]


def read_ids(path):
    """A file of one integer per line (a .map or .vts file, 1-based) as 0-based ids."""
    return np.loadtxt(path, dtype=np.int64, ndmin=1) - 1


@pytest.fixture(scope="session")
def binary():
    path = os.environ.get("SYMEMBED_BINARY")
    if not path:
        pytest.fail("SYMEMBED_BINARY is not set: run these tests through ctest (label python)")
    return path


def run_binary(binary, *args, check=True):
    """Runs the binary with args; returns the CompletedProcess (text stdout and stderr)."""
    done = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"symembed {' '.join(map(str, args))} exited {done.returncode}:\n"
                             f"{done.stderr}")
    return done


def write_config(path, root, options, name="pair", variants=""):
    """A config for the pairs_vts dataset at root with options {dotted.path: value}."""
    lines = [f"name: {name}", f"dataset: {{format: pairs_vts, root: {root}}}"]
    sections = {}
    for key, value in options.items():
        parts = key.split(".")
        assert parts[0] == "pipeline" and len(parts) == 3, key
        sections.setdefault(parts[1], []).append(f"{parts[2]}: {value}")
    if sections:
        lines.append("pipeline:")
        lines += [f"  {kind}: {{{', '.join(items)}}}" for kind, items in sections.items()]
    path.write_text("\n".join(lines) + "\n" + variants)
    return path


@pytest.fixture(scope="session")
def pair(tmp_path_factory, binary):
    """Two poses of the synthetic humanoid, their ground truth, and the binary's runs of the
    pair with PAIR_OPTIONS and with every option at its default (their maps, 0-based)."""
    tmp = tmp_path_factory.mktemp("pair")
    root = tmp / "synth"
    run_binary(binary, "synth", "--kind", "humanoid", "--poses", 2, "--vertices", 800,
               "--out", root)
    with open(root / "test_pairs.txt") as f:
        a, b = f.readline().split()[:2]
    config = write_config(tmp / "pair.yaml", root, PAIR_OPTIONS)
    out = tmp / "run"
    run_binary(binary, "run", config, "--out", out, "--cache", "", "--quiet", "--no-report")
    defaults = write_config(tmp / "defaults.yaml", root, {}, name="defaults")
    run_binary(binary, "run", defaults, "--out", tmp / "defaults", "--cache", "", "--quiet",
               "--no-report")
    VA, FA = read_off(root / "shapes" / f"{a}.off")
    VB, FB = read_off(root / "shapes" / f"{b}.off")
    return types.SimpleNamespace(
        root=root, a=a, b=b, VA=VA, FA=FA, VB=VB, FB=FB, config=config, out=out,
        cli_map=read_ids(out / "base" / "maps" / f"{a}_{b}.map"),
        cli_map_defaults=read_ids(tmp / "defaults" / "base" / "maps" / f"{a}_{b}.map"),
        gt_a=read_ids(root / "corres" / f"{a}.vts"),
        gt_b=read_ids(root / "corres" / f"{b}.vts"))


@pytest.fixture(scope="session")
def shapes(pair):
    """The pair as symembed.Shape objects computed with PAIR_OPTIONS."""
    import symembed

    return (symembed.Shape(pair.VA, pair.FA, PAIR_OPTIONS, name=pair.a),
            symembed.Shape(pair.VB, pair.FB, PAIR_OPTIONS, name=pair.b))
