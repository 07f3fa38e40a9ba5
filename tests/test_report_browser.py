"""The report in a real headless browser: no console errors, every figure drawn inside its
card, a screenshot that is not blank. Skips (saying why) only when no Chromium is installed;
test_report.py checks the page's structure without a browser either way."""

from __future__ import annotations

import io

import pytest

from report.ggc import main as ggc

from browser import Browser, find_chromium
from conftest import CORPUS, ROOT

PIL = pytest.importorskip("PIL.Image")
CHROMIUM = find_chromium()
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="no chromium binary on PATH "
                                "(install it, e.g. apt-get install chromium, to run this test)")

# For every rule card and every image: its figure's box, and the card's box.
MEASURE = """(async () => {
  const imgs = [...document.querySelectorAll('img')];
  for (const i of imgs) i.loading = 'eager';
  await Promise.all(imgs.map(i => i.decode().catch(() => null)));
  const out = [];
  for (const card of document.querySelectorAll('.card')) {
    card.scrollIntoView();
    const fig = card.querySelector('svg, img');
    const c = card.getBoundingClientRect(), f = fig ? fig.getBoundingClientRect() : null;
    out.push({id: card.id, rule: card.classList.contains('rule'), has: !!fig,
              img: fig && fig.tagName === 'IMG' ? fig.complete && fig.naturalWidth > 0 : true,
              f: f && [f.left, f.top, f.right, f.bottom], c: [c.left, c.top, c.right, c.bottom]});
  }
  window.scrollTo(0, 0);
  return out;
})()"""


@pytest.fixture(scope="module")
def browser():
    b = Browser(CHROMIUM)
    yield b
    b.close()


@pytest.mark.parametrize("path", [ROOT / "examples" / "castle.gg", ROOT / "examples" / "house.gg",
                                  CORPUS / "star-filled.svg"])
def test_report_renders_in_a_browser(path, tmp_path, browser):
    out = tmp_path / "r.html"
    assert ggc(["report", str(path), "-o", str(out), "--gallery", "2", "--steps", "40"]) == 0
    browser.load(out.as_uri())
    cards = browser.evaluate(MEASURE)
    assert browser.errors() == []
    rules = [c for c in cards if c["rule"]]
    assert rules and all(c["has"] for c in rules), "every rule has an image"
    for c in cards:
        if not c["has"]:
            continue
        (fl, ft, fr, fb), (cl, ct, cr, cb) = c["f"], c["c"]
        assert c["img"], f"{c['id']}: an image did not load"
        assert fr - fl > 4 and fb - ft > 4, f"{c['id']}: empty figure"
        assert cl - 0.5 <= fl and fr <= cr + 0.5 and ct - 0.5 <= ft and fb <= cb + 0.5, \
            f"{c['id']}: figure outside its card"
    im = PIL.open(io.BytesIO(browser.screenshot())).convert("L")
    lo, hi = im.getextrema()
    assert hi - lo > 100, "the screenshot is blank"
