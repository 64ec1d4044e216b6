"""mkdocs hook: the viewer itself on the site, next to the pages that frame it.

After the build, writes ``view/heavy_top.view.html`` into the site: the page
``ga-rotors view heavy_top`` writes (self-contained, about 0.45 MB, drawn by the package's own
script), which docs/view.md shows in a frame, so a reader turns the heavy top and plays its
run in the browser; and ``learn/motors/thrown_racket.view.html``, the thrown racket of the
learning path's last page (docs/learn/motors.md). The bundled scenes run here (a few
seconds once their loops are compiled and cached).
"""

from __future__ import annotations

import os

os.environ.setdefault("MPLBACKEND", "Agg")

#: site path of the page, relative to the site's root.
PAGE = os.path.join("view", "heavy_top.view.html")
#: bundled scene -> the site path of its page.
PAGES = {"heavy_top": PAGE, "thrown_racket": os.path.join("learn", "motors",
                                                          "thrown_racket.view.html")}


def on_post_build(config) -> None:
    from ga_rotors.scene import load_scene
    from ga_rotors.view import View

    for name, page in PAGES.items():
        View.from_scene(load_scene(name)).save(os.path.join(config["site_dir"], page))
