"""One vocabulary: the example, the grammar header, the verifier's reference and the runtime's
tables embed the same value, and read its fields through."""

from dataclasses import replace

from grammar_lang.rules import Header
from grammar_lang.vocabulary import Vocabulary
from runtime.geometry.tables import Tables
from runtime.verifier import as_reference
from tests.hand_examples import RECTANGLE, make


def test_every_holder_reads_the_one_vocabulary():
    ex = make(RECTANGLE)
    header = Header(source="x", vocabulary=ex.vocabulary, options=ex.options)
    ref, tables = as_reference(ex), Tables.build(header)
    for holder in (ex, header, ref, tables):
        assert holder.labels == ex.vocabulary.labels
        assert holder.primitives == ex.vocabulary.primitives
        assert holder.exterior == "exterior" and holder.face_labels == ("exterior",)
        assert holder.label_names == ("x", "y")
        assert holder.format(holder.primitives[0].ring) == ex.vocabulary.format((3, 0))
    assert header.vocabulary is ex.vocabulary and tables.vocabulary == ex.vocabulary


def test_a_missing_unit_reads_as_one_where_lengths_are_measured():
    v = Vocabulary("exterior", ("exterior",), unit=0.0)
    header = Header(vocabulary=v)
    assert header.unit == 0.0                              # the file's own value is kept
    assert Tables.build(header).unit == 1.0 and as_reference(header).unit == 1.0
    assert replace(v, unit=2.0).unit == 2.0
