"""docs/make_gallery.py, which writes docs/gallery.md, runs as shipped (in its quick mode)."""

import importlib.util
import re
import sys

from conftest import ROOT


def test_the_gallery_script_draws_every_scene(tmp_path):
    spec = importlib.util.spec_from_file_location("make_gallery", ROOT / "docs" / "make_gallery.py")
    gallery = importlib.util.module_from_spec(spec)
    sys.modules["make_gallery"] = gallery       # its dataclasses look their module up
    spec.loader.exec_module(gallery)
    page = tmp_path / "gallery.md"
    assert gallery.main(["--quick", "--out", str(tmp_path / "img"), "--page", str(page)]) == 0
    text = page.read_text()
    for s in gallery.SCENES:
        assert f"### {s.name}" in text
        assert (tmp_path / "img" / f"{s.name}-example.png").read_bytes()[:4] == b"\x89PNG"
    # Every picture the page shows exists; a run that wrote none says why.
    for ref in re.findall(r"\]\((img/[^)]+)\)", text):
        assert (tmp_path / ref).read_bytes()[:4] == b"\x89PNG"
    assert text.count("(no drawing)") == text.count("error:")
