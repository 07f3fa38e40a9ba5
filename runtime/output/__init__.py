"""What a run writes: the drawing value and its JSON (`drawing`), SVG (`svg_out`, with edges
bent as decorations ask by `bending`, and `free_svg` for hand-written productions) and
GraphML (`graphml_out`)."""
