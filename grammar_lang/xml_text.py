"""Text for the XML the tools write (SVG, GraphML, the report's pages).

XML 1.0 holds only the characters of its `Char` production: tab, line feed, carriage return,
U+0020–U+D7FF, U+E000–U+FFFD and U+10000 up. Escaping cannot carry the others (a character
reference to one is an error too), so a name or decoration from a user's file that holds one
(a `.ggr` string may spell any code point, `\\uFFFE` or `\\u0001`) would make the whole file
unreadable. Such a character is written as U+FFFD, the replacement character, before any
escaping.
"""

from __future__ import annotations

import re

_NOT_XML = re.compile("[^\t\n\r\u0020-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def xml_text(text: str) -> str:
    """`text` with every character XML 1.0 cannot hold replaced by U+FFFD."""
    return _NOT_XML.sub("\ufffd", text)
