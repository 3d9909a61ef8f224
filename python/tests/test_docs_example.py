"""docs/python.md's complete example, run as a new user would: its shell block (with the binary
under test as $SYMEMBED), then its Python block, in an empty folder. It must print that the map
from numpy is the binary's."""

import os
import pathlib
import re
import subprocess
import sys

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"


def example_blocks():
    """The ```sh and ```python blocks of the section "A complete example", in order."""
    text = DOC.read_text()
    section = text.split("## A complete example", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```(sh|python)\n(.*?)```", section, flags=re.S)


def test_the_example_has_a_shell_and_a_python_block():
    kinds = [kind for kind, _ in example_blocks()]
    assert kinds == ["sh", "python"], kinds


def test_the_complete_example_gives_the_binarys_map(binary, tmp_path):
    (_, shell), (_, python) = example_blocks()
    env = dict(os.environ, SYMEMBED=os.path.abspath(binary), MPLBACKEND="Agg")
    subprocess.run(["bash", "-euo", "pipefail", "-c", shell], cwd=tmp_path, env=env, check=True,
                   stdout=subprocess.DEVNULL)
    script = tmp_path / "example.py"
    script.write_text(python)
    out = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, check=True,
                         capture_output=True, text=True).stdout
    assert "same map as the binary: True" in out, out
    assert "mean error" in out, out
