"""The parsers' LALR tables kept between processes (grammar_lang.lark_cache)."""

from pathlib import Path

import lark
import pytest

from grammar_lang import gg_parser, ggr_parser
from grammar_lang.lark_cache import lalr_parser

ROOT = Path(__file__).resolve().parent.parent
GG = Path(gg_parser.__file__).with_name("gg_grammar.lark")
GGR = Path(ggr_parser.__file__).with_name("ggr_grammar.lark")
GG_TEXTS = [p.read_text(encoding="utf-8") for p in sorted((ROOT / "examples").glob("*.gg"))]


def _ggr_texts() -> list[str]:
    from compiler.infer import compile_example
    from grammar_lang.ggr_emit import emit_ggr
    from grammar_lang.loader import load_example
    names = ["tree.gg", "house.gg", "castle.gg"]
    return [emit_ggr(compile_example(load_example(ROOT / "examples" / n)).grammar)
            for n in names] + ["ggr 1\nrule r0 {", "ggr 9\n"]


def _gg():
    return lalr_parser(GG, {"postlex": gg_parser._Lines()}, propagate_positions=True,
                       maybe_placeholders=False)


def _parse(parser, text):
    try:
        return parser.parse(text)
    except lark.exceptions.LarkError as e:      # the same error, at the same place
        return type(e).__name__, getattr(e, "line", None), getattr(e, "column", None)


def test_a_loaded_parser_parses_as_a_built_one(tmp_path, monkeypatch):
    monkeypatch.setenv("GG_CACHE_DIR", str(tmp_path))
    built = _gg()
    assert len(list(tmp_path.glob("gg_grammar-*.json"))) == 1
    # The second parser must come from the file: building is made to fail.
    monkeypatch.setattr("grammar_lang.lark_cache.Lark.__init__",
                        lambda *a, **k: pytest.fail("built instead of loaded"))
    loaded = _gg()
    texts = GG_TEXTS + ["example \"x\"\nface a {\n", "class 0 { min: }"]
    assert len(GG_TEXTS) >= 5
    for text in texts:
        assert _parse(loaded, text) == _parse(built, text)


def test_the_ggr_tables_round_trip(tmp_path, monkeypatch):
    monkeypatch.setenv("GG_CACHE_DIR", str(tmp_path))
    built = lalr_parser(GGR, propagate_positions=False)
    loaded = lalr_parser(GGR, propagate_positions=False)
    assert loaded is not built
    for text in _ggr_texts():
        assert _parse(loaded, text) == _parse(built, text)


def test_a_torn_or_foreign_cache_file_is_rebuilt(tmp_path, monkeypatch):
    monkeypatch.setenv("GG_CACHE_DIR", str(tmp_path))
    _gg()
    (path,) = tmp_path.glob("gg_grammar-*.json")
    for junk in ("{\"key\": ", "[]", "{\"key\": \"other\", \"tables\": {}}",
                 path.read_text()[:-200]):
        path.write_text(junk)
        assert _parse(_gg(), GG_TEXTS[0]) == _parse(gg_parser._lark(), GG_TEXTS[0])


def test_the_cache_can_be_turned_off_or_be_unwritable(tmp_path, monkeypatch):
    home = tmp_path / "home"
    monkeypatch.setenv("XDG_CACHE_HOME", str(home))
    monkeypatch.setenv("GG_CACHE_DIR", "off")
    _gg()
    assert not home.exists()                 # off: nothing written, not even the default place
    monkeypatch.delenv("GG_CACHE_DIR")
    _gg()
    assert list(home.rglob("gg_grammar-*.json"))     # the default place, when it is on
    monkeypatch.setenv("GG_CACHE_DIR", str(tmp_path / "file"))
    (tmp_path / "file").write_text("not a directory")
    assert _parse(_gg(), GG_TEXTS[0]) == _parse(gg_parser._lark(), GG_TEXTS[0])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file", "home"]
