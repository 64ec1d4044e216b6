"""mkdocs hook: the viewer itself on the site, next to docs/view.md.

After the build, writes ``view/heavy_top.view.html`` into the site: the page
``ga-rotors view heavy_top`` writes (self-contained, about 0.45 MB, drawn by the package's own
script), which docs/view.md shows in a frame, so a reader turns the heavy top and plays its
run in the browser. The bundled scene runs here (a few seconds once its loops are compiled
and cached).
"""

from __future__ import annotations

import os

os.environ.setdefault("MPLBACKEND", "Agg")

#: site path of the page, relative to the site's root.
PAGE = os.path.join("view", "heavy_top.view.html")


def on_post_build(config) -> None:
    from ga_rotors.scene import load_scene
    from ga_rotors.view import View

    View.from_scene(load_scene("heavy_top")).save(os.path.join(config["site_dir"], PAGE))
