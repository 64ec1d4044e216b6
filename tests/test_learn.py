"""The learning path's pictures: drawn by ga_rotors.view.diagrams, committed, shown on a page.

The exercises' worked solutions on docs/learn/*.md run in tests/test_docs.py.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from ga_rotors.errors import InputError
from ga_rotors.view.diagrams import PICTURES, draw_all, reflect

LEARN = Path(__file__).resolve().parents[1] / "docs" / "learn"


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    return draw_all(tmp_path_factory.mktemp("pictures"))


def test_every_picture_is_drawn_legibly(drawn):
    from PIL import Image

    assert [p.stem for p in drawn] == list(PICTURES)
    for path in drawn:
        with Image.open(path) as image:
            assert image.info["dpi"][0] == pytest.approx(150, abs=0.5), path.name
            assert min(image.size) >= 450, path.name
            pixels = np.asarray(image.convert("RGB")).reshape(-1, 3)
            colours = np.unique(pixels, axis=0).shape[0]
            assert colours > 50, f"{path.name} looks blank ({colours} colours)"


def test_every_picture_is_committed_and_shown_on_a_page():
    committed = {p.stem for p in (LEARN / "images").glob("*.png")}
    assert committed == set(PICTURES), "run: python -m ga_rotors.view.diagrams docs/learn/images"
    shown = set()
    for page in LEARN.glob("*.md"):
        shown |= set(re.findall(r"\]\(images/(\w+)\.png\)", page.read_text(encoding="utf-8")))
    assert shown == set(PICTURES)


def test_vector_formats_on_request(tmp_path):
    (svg,) = draw_all(tmp_path, fmt="svg", names=["reflection"])
    assert svg.read_text(encoding="utf-8").lstrip().startswith("<?xml")
    (pdf,) = draw_all(tmp_path, fmt="pdf", names=["reflection"])
    assert pdf.read_bytes().startswith(b"%PDF")
    with pytest.raises(InputError, match="fmt"):
        draw_all(tmp_path, fmt="gif", names=["reflection"])


def test_the_pages_of_the_path_are_linked_from_its_index():
    index = (LEARN / "index.md").read_text(encoding="utf-8")
    pages = {p.name for p in LEARN.glob("*.md")} - {"index.md"}
    assert set(re.findall(r"\]\(([\w-]+\.md)\)", index)) == pages


finite = st.floats(-10, 10, allow_nan=False)


@given(arrays(np.float64, 3, elements=finite), arrays(np.float64, 3, elements=finite))
def test_reflection_is_the_linear_algebra_mirror(v, n):
    if np.linalg.norm(n) < 1e-3:
        return
    u = n / np.linalg.norm(n)
    image = reflect(v, n)
    scale = 1e-12 * (1 + np.linalg.norm(v))
    assert np.allclose(image, v - 2 * (v @ u) * u, atol=scale)
    assert np.allclose(reflect(image, n), v, atol=scale)
