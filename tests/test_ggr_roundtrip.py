"""`.ggr` round trips: parse(emit(g)) == g for generated grammars, real example headers, the
documentation's examples, and the hand-edit protection of `write_ggr`."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import CORPUS
from hypothesis import HealthCheck, given, settings, strategies as st

from ggr_strategies import WORDS, grammars, renumbered, sides
from grammar_lang.diagnostics import UserError
from grammar_lang.ggr_emit import emit_ggr
from grammar_lang.ggr_file import edit_state, write_ggr
from grammar_lang.ggr_parser import load_ggr, parse_ggr
from grammar_lang.rules import Grammar, Rule

ROOT = Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "ggr-language.md"


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(grammars())
def test_parse_of_emit_is_identity(grammar):
    text = emit_ggr(grammar)
    back = parse_ggr(text, "gen.ggr")
    assert back == grammar
    # Emitting again is byte-identical, and the checksum says "not edited".
    assert emit_ggr(back) == text
    assert edit_state(text) == "generated"


@settings(max_examples=60, deadline=None)
@given(grammars(), st.data())
def test_any_change_to_the_text_is_an_edit(grammar, data):
    text = emit_ggr(grammar)
    lines = text.splitlines(keepends=True)
    k = data.draw(st.integers(0, len(lines) - 1))
    if lines[k].startswith("checksum "):
        return
    edited = "".join(lines[:k] + [lines[k].rstrip("\n") + " # note\n"] + lines[k + 1:])
    assert edit_state(edited) == "edited"


def corpus_headers():
    """Headers of the real corpus examples, typed by grammar_lang.labelling."""
    from grammar_lang.loader import load_example
    from grammar_lang.rules import Header
    out = []
    for path in sorted(CORPUS.glob("*.json")):
        ex = load_example(path)
        out.append(pytest.param(Header(
            source=str(path.name), source_hash="sha256:0", compiler_version="test",
            vocabulary=ex.vocabulary, options=ex.options, decorations=ex.decorations),
            id=path.stem))
    return out


@pytest.mark.parametrize("header", corpus_headers() if CORPUS.is_dir() else [])
@settings(max_examples=8, deadline=None)
@given(data=st.data())
def test_corpus_headers_round_trip_with_random_rules(header, data):
    rules = []
    for k in range(data.draw(st.integers(1, 3))):
        rhs = data.draw(sides(header))
        rules.append(Rule(f"r{k}", data.draw(renumbered(rhs)), rhs, k, 1.0))
    grammar = Grammar(header, tuple(rules))
    assert parse_ggr(emit_ggr(grammar)) == grammar


@pytest.mark.parametrize("path", sorted((ROOT / "examples").glob("*.gg")), ids=lambda p: p.stem)
def test_shipped_example_headers_round_trip(path):
    """Headers as the .gg front end makes them: decorations, classes, options, faces."""
    from grammar_lang.loader import load_example
    from grammar_lang.rules import Header
    ex = load_example(path)
    header = Header(source=str(path.name), vocabulary=ex.vocabulary, options=ex.options,
                    decorations=ex.decorations)
    grammar = Grammar(header, ())
    assert parse_ggr(emit_ggr(grammar)) == grammar


def _named_with_keywords(header):
    """`header` with its labels, primitives, face labels and classes renamed to the words of
    the language (WORDS), as far as they go round (then with a `_` or more after them)."""
    import dataclasses

    def word(k: int) -> str:
        return WORDS[k % len(WORDS)] + "_" * (k // len(WORDS))

    voc = header.vocabulary
    faces = {f: word(k) for k, f in enumerate((voc.exterior, *voc.face_labels))}
    classes = {c.name: word(k + 5) for k, c in enumerate(voc.classes)}
    labels = tuple(dataclasses.replace(l, name=word(k + 3), left=faces[l.left],
                                       right=faces[l.right], cls=classes.get(l.cls, l.cls))
                   for k, l in enumerate(voc.labels))
    prims = tuple(dataclasses.replace(p, name=word(k + 7)) for k, p in enumerate(voc.primitives))
    voc = dataclasses.replace(
        voc, exterior=faces[voc.exterior], face_labels=tuple(faces[f] for f in voc.face_labels),
        classes=tuple(dataclasses.replace(c, name=classes[c.name]) for c in voc.classes),
        labels=labels, primitives=prims)
    return dataclasses.replace(header, vocabulary=voc, decorations=())


@pytest.mark.parametrize("name", ["house", "castle-scene", "space-station"])
def test_names_spelled_like_the_languages_words_round_trip(name):
    """Names are written bare where they are plain identifiers, the language's own words too:
    a label named `face` second in a primitive's ring used to be read as a production's
    `face` keyword (LALR merged the states that end a name in both places)."""
    from grammar_lang.loader import load_example
    from grammar_lang.rules import Header
    ex = load_example(ROOT / "examples" / f"{name}.gg")
    header = _named_with_keywords(Header(source=name, vocabulary=ex.vocabulary,
                                         options=ex.options))
    grammar = Grammar(header, ())
    text = emit_ggr(grammar)
    assert re.search(r"^primitive \S+ = \S+ ~?face ", text, re.M)     # `face` second in a ring
    assert parse_ggr(text) == grammar


def doc_blocks():
    text = DOC.read_text(encoding="utf-8")
    return [(text[:m.start()].count("\n") + 2, m.group(1))
            for m in re.finditer(r"```ggr\n(.*?)```", text, re.S)]


def test_the_documentation_has_examples():
    assert len(doc_blocks()) >= 3


@pytest.mark.parametrize("line,block", doc_blocks() if DOC.exists() else [])
def test_documentation_examples_parse_and_round_trip(line, block):
    try:
        grammar = parse_ggr(block, f"{DOC.name}:{line}")
    except UserError as exc:
        pytest.fail(f"block at {DOC.name}:{line} does not parse:\n{exc.render()}")
    assert parse_ggr(emit_ggr(grammar)) == grammar


# --- write_ggr: hand edits are never lost -----------------------------------------------------

@settings(max_examples=5, deadline=None)
@given(grammars())
def test_write_refuses_edited_and_foreign_files(tmp_path_factory, grammar):
    path = tmp_path_factory.mktemp("w") / "out.ggr"
    write_ggr(path, grammar)
    assert load_ggr(path) == grammar
    write_ggr(path, grammar)                 # unchanged since written: may be replaced
    edited = path.read_text(encoding="utf-8") + "# my note\n"
    path.write_text(edited, encoding="utf-8")
    with pytest.raises(UserError) as info:
        write_ggr(path, grammar)
    assert "edited" in info.value.render() and "--force" in info.value.render()
    assert path.read_text(encoding="utf-8") == edited
    write_ggr(path, grammar, force=True)
    assert edit_state(path.read_text(encoding="utf-8")) == "generated"
    other = path.with_name("notes.ggr")
    other.write_text("my own notes\n", encoding="utf-8")
    with pytest.raises(UserError) as info:
        write_ggr(other, grammar)
    assert "not a .ggr file generated" in info.value.render()
    assert other.read_text(encoding="utf-8") == "my own notes\n"
    # Atomic writes leave no temporary files behind.
    assert sorted(p.name for p in path.parent.iterdir()) == ["notes.ggr", "out.ggr"]


def test_crlf_line_endings_do_not_count_as_an_edit(tmp_path):
    grammar = parse_ggr(doc_blocks()[0][1])
    text = emit_ggr(grammar)
    assert edit_state(text.replace("\n", "\r\n")) == "generated"


def test_write_refuses_unreadable_existing_path(tmp_path):
    grammar = parse_ggr(doc_blocks()[0][1])
    target = tmp_path / "dir.ggr"
    target.mkdir()
    with pytest.raises(UserError):
        write_ggr(target, grammar)


# --- grammars the compiler infers from the corpus ---------------------------------------------

# Examples that compile in well under a second, with a spread of rule kinds: wires, spliced
# sides, starters, rules with several components.
COMPILED = ["square-hollow", "curl", "star-hollow", "double-branch", "diagonal-row", "plus",
            "intersection", "triangle-square", "star-filled", "u"]


@pytest.mark.parametrize("stem", COMPILED)
def test_compiled_corpus_grammars_validate_and_round_trip(stem, tmp_path):
    from compiler.infer import compile_example
    from grammar_lang.loader import load_example
    grammar = compile_example(load_example(CORPUS / f"{stem}.json")).grammar
    assert grammar.rules
    path = tmp_path / f"{stem}.ggr"
    write_ggr(path, grammar)
    assert load_ggr(path) == grammar


def test_digit_like_names_are_names_not_slot_indices():
    # '²' is a letter-like digit: a name (not \d), though str.isdigit() says otherwise.
    text = ("ggr 1\nfaces a\nlabel ² angle=0 left=a right=a\nprimitive p = ²\nprimitive q = ~²\n"
            "starter s {\n  lhs {\n    a: p  b: q\n    a.² -- b.0\n    boundary +\n  }\n}\n")
    grammar = parse_ggr(text)
    assert grammar.rules[0].lhs.edges == ((0, 0, 1, 0),)
    assert parse_ggr(emit_ggr(grammar)) == grammar
