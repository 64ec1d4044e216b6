"""docs/motors.md's picture is what the page's code draws (tests/test_docs.py runs the code;
this checks the committed image is its current output). Regenerate with
``python tests/test_motor_docs.py``."""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

import numpy as np

PAGE = Path(__file__).resolve().parents[1] / "docs" / "motors.md"
IMAGE = PAGE.parent / "images" / "motor_screw.png"
FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)


def draw(folder: Path) -> Path:
    """Run the page's first block (its imports) and its picture block in ``folder``."""
    blocks = FENCE.findall(PAGE.read_text(encoding="utf-8"))
    (picture,) = [b for b in blocks if IMAGE.name in b]
    namespace = {"__name__": "docs_motors_picture"}
    here = os.getcwd()
    os.chdir(folder)
    try:
        for code in (blocks[0], picture):
            exec(compile(code, str(PAGE), "exec"), namespace)
    finally:
        os.chdir(here)
    return folder / IMAGE.name


def test_the_committed_picture_is_the_pages_code_output(tmp_path):
    from PIL import Image

    assert f"](images/{IMAGE.name})" in PAGE.read_text(encoding="utf-8")
    drawn = np.asarray(Image.open(draw(tmp_path)).convert("L"), dtype=float)
    committed = np.asarray(Image.open(IMAGE).convert("L"), dtype=float)
    assert drawn.shape == committed.shape, "run: python tests/test_motor_docs.py"
    # Renderers differ by anti-aliasing between versions; a changed picture differs by far more.
    assert np.abs(drawn - committed).mean() < 2.0, "run: python tests/test_motor_docs.py"


if __name__ == "__main__":
    sys.exit(print("wrote", draw(IMAGE.parent)))
