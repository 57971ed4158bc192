# SPDX-License-Identifier: Apache-2.0
"""Every ```python block of the repository's README runs, so that its examples cannot drift
from the package. A block runs in a fresh temporary folder holding links to the repository's
data folders (the examples name paths relative to the repository root), so files it writes
land there, not in the checkout."""
import os
import re
import runpy

import pytest

from conftest import REPO

README = REPO / "README.md"


def python_blocks():
    """(first line number, source) of each ```python block."""
    text = README.read_text(encoding="utf-8")
    blocks = []
    for match in re.finditer(r"^```python\n(.*?)^```$", text, flags=re.S | re.M):
        line = text.count("\n", 0, match.start()) + 2
        blocks.append(pytest.param(match.group(1), id=f"README.md:{line}"))
    return blocks


def test_readme_has_python_blocks():
    assert python_blocks(), "the README has no ```python block"


@pytest.mark.parametrize("source", python_blocks())
def test_readme_python_block(source, tmp_path, monkeypatch, capsys):
    if "libppm.distributed" in source:
        pytest.importorskip("dask.distributed", reason="the Dask extra is not installed")
    for folder in ("tests", "examples"):
        (tmp_path / folder).symlink_to(REPO / folder, target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    script = tmp_path / "block.py"
    script.write_text(source, encoding="utf-8")
    runpy.run_path(os.fspath(script), run_name="__main__")
    capsys.readouterr()  # what the example prints is for a reader; running it is the test
