"""Escaping and number formatting for the HTML and SVG the report writes."""

from __future__ import annotations

import html

from grammar_lang.xml_text import xml_text


def esc(text: object) -> str:
    """Every piece of text from a user's file goes through here into HTML or SVG (element
    content and quoted attribute values alike), with what XML cannot hold replaced."""
    return html.escape(xml_text(str(text)), quote=True)


def num(x: float) -> str:
    """Coordinates in px with 6 decimals (directions stay exact to ~1e-8), no exponents."""
    text = f"{x:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text
