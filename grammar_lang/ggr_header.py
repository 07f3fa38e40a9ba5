"""The header of a `.ggr` file: faces, edge classes, labels, primitives, decorations,
options and the labels and attributes of hand-written productions, resolved and checked."""

from __future__ import annotations

import dataclasses
from pathlib import Path

from lark import Token, Tree

from . import boundary as bd
from . import ggr_free
from .diagnostics import UserError, did_you_mean
from .vocabulary import EdgeLabel, Primitive, Vocabulary
from .frame import Corner, Frame
from .gg_schema import check_decoration
from .ggr_reader import Reader, _Stop
from .rules import Header
from .source import DEFAULT_CLASS, Decoration, EdgeClass, Limits, Options

# Coordinates are bounded by ±1e12 and written to 1e-8; a unit outside this breaks arithmetic.
MIN_UNIT, MAX_UNIT = 1e-6, 1e12

FORMAT_VERSION = 1
_VOCABULARY = tuple(f.name for f in dataclasses.fields(Vocabulary))


class HeaderReader(Reader):
    def _header(self, singles: dict[str, Tree], lists: dict[str, list[Tree]]) -> Header:
        fields = self._statements(singles)
        exterior = self.name(singles["exterior"].children[0]) if "exterior" in singles \
            else "exterior"
        fields["exterior"] = exterior
        faces: list[str] = []
        for tok in singles["faces"].children if "faces" in singles else ():
            face = self.name(tok)
            if face in faces:
                self.fail(f"face label '{face}' is listed twice", tok)
            faces.append(face)
        fields["face_labels"] = tuple(faces)
        fields.update(self._definitions(lists, set(faces) | {exterior}))
        fields.update(self._free_header(singles, lists))
        targets = {"face": set(faces) | {exterior},
                   "edge": {c.name for c in fields["classes"]} | {DEFAULT_CLASS}
                   | set(fields["edge_labels"]),
                   "vertex": {p.name for p in fields["primitives"]} | set(fields["vertex_labels"])}
        fields["decorations"] = tuple(d for d in (self._guard(self._decoration, n, targets)
                                                  for n in lists["decorate"]) if d)
        if "frame" in singles:
            fields["frame"] = self._frame(singles["frame"], fields["primitives"])
        vocabulary = Vocabulary(**{k: fields.pop(k) for k in _VOCABULARY if k in fields})
        return Header(vocabulary=vocabulary, **fields)

    def _frame(self, node: Tree, prims) -> Frame:
        """`frame P x y P x y …`: the corners of the border, in order round it."""
        index = {p.name: k for k, p in enumerate(prims)}
        parts, corners = node.children, []
        for k in range(0, len(parts), 3):
            tok, x, y = parts[k:k + 3]
            name = self.name(tok)
            if name not in index:
                self.fail(f"unknown primitive '{name}' in the frame", tok,
                          did_you_mean(name, index) or "a corner is one of the primitives above")
            corners.append(Corner(index[name], self.number(x), self.number(y)))
        if len(corners) < 3:
            self.fail("a frame has at least three corners", self._first_token(node))
        return Frame(tuple(corners))

    def _statements(self, singles: dict[str, Tree]) -> dict[str, object]:
        """The statements that stand once: version, source, compiler, mode, status, unit,
        options and limits."""
        version = singles["version"].children[0]
        if self.integer(version) != FORMAT_VERSION:
            self.fail(f"this tool reads .ggr version {FORMAT_VERSION}, not {version}", version,
                      "regenerate the file with this version of ggc")
        fields: dict[str, object] = {}
        if "source" in singles:
            node = singles["source"].children
            fields["source"] = self.name(node[0])
            if len(node) > 1:
                fields["source_hash"] = self.name(node[1])
        if "compiler" in singles:
            fields["compiler_version"] = self.name(singles["compiler"].children[0])
        if "mode" in singles:
            tok = singles["mode"].children[0]
            mode = self.name(tok)
            if mode not in ("dpo", "spo"):
                self.fail(f"unknown mode '{mode}'", tok,
                          "dpo (a rule needs its gluing conditions) or spo (dangling edges are deleted)")
            fields["mode"] = mode
        if "status" in singles:
            tok = singles["status"].children[0]
            status = self.name(tok)
            if status not in _STATUS:
                self.fail(f"unknown status '{status}'", tok,
                          did_you_mean(status, _STATUS) or "complete, limited or unknown")
            fields["complete"] = _STATUS.get(status)
        if "unit" in singles:
            tok = singles["unit"].children[0]
            unit = self._guard(self.number, tok)
            if unit is not None and not MIN_UNIT <= unit <= MAX_UNIT:
                self.fail(f"the unit must be from {MIN_UNIT:g} to {MAX_UNIT:g}", tok,
                          "the unit is a typical edge length (the example's median edge)")
            fields["unit"] = unit if unit is not None else 1.0
        if "options" in singles or "limits" in singles:
            fields["options"] = self._options(singles.get("options"), singles.get("limits"))
        return fields

    def _definitions(self, lists: dict[str, list[Tree]], known_faces: set[str]) -> dict:
        """Edge classes, edge labels and primitives."""
        classes = self._defined(self._edge_class, lists["edge_class"])
        fields: dict[str, object] = {"classes": tuple(classes)}
        class_names = {c.name for c in classes} | {DEFAULT_CLASS}
        labels = self._defined(self._label, lists["label"], known_faces, class_names)
        fields["labels"] = tuple(labels)
        if any(l.cls == DEFAULT_CLASS for l in labels) and DEFAULT_CLASS not in \
                {c.name for c in classes}:
            # The default class exists without a line of its own; list it like the others so
            # that every class a label uses is in the header.
            fields["classes"] = tuple(classes) + (EdgeClass(DEFAULT_CLASS),)
        self._unique(lists["label"], "edge label")
        self._unique(lists["edge_class"], "edge class")
        label_ids = {l.name: i for i, l in enumerate(labels)}
        prims = self._defined(self._primitive, lists["primitive"], labels, label_ids)
        self._unique(lists["primitive"], "primitive")
        fields["primitives"] = tuple(prims)
        return fields

    def _free_header(self, singles: dict[str, Tree], lists: dict[str, list[Tree]]) -> dict:
        """The vertex and edge labels and the attributes of hand-written productions."""
        declared: dict = {}
        reader = ggr_free.FreeReader(self)
        attributes = tuple(a for a in (self._guard(reader.attribute, n, declared)
                                       for n in lists["attribute"]) if a)
        return {"vertex_labels": self._label_list(singles.get("vertex_labels")),
                "edge_labels": self._label_list(singles.get("edge_labels")),
                "attributes": attributes}

    def _options(self, options: Tree | None, limits: Tree | None) -> Options:
        opts = self.settings(options.children if options else [], _OPTION_KEYS, "options") \
            if options else {}
        lims = self.settings(limits.children if limits else [], _LIMIT_KEYS, "limits") \
            if limits else {}
        for key, value in list(opts.items()) + list(lims.items()):
            if value is not None and value < 0:
                node = options if key in opts else limits
                tok = self._key(node.children, key)
                self.fail(f"'{key}' cannot be negative", tok)
        return Options(**opts, limits=Limits(**lims))

    def _edge_class(self, node: Tree) -> EdgeClass:
        tok, *rest = node.children
        s = self.settings(rest, _CLASS_KEYS, "an edge class")
        for key in ("min", "max", "fixed", "tile"):
            if s.get(key) is not None and s[key] <= 0:
                key_tok = self._key(rest, key)
                raise self.fail(f"'{key}' must be a positive length", key_tok)
        if s.get("min") is not None and s.get("max") is not None and s["min"] > s["max"]:
            raise self.fail("min is greater than max", tok)
        return EdgeClass(self.name(tok), s.get("min"), s.get("max"), s.get("fixed"),
                         s.get("tile"), s.get("rigid", False), s.get("border", False),
                         span=self.span(tok))

    def _label(self, node: Tree, faces: set[str], classes: set[str]) -> EdgeLabel:
        tok, *rest = node.children
        s = self.settings(rest, _LABEL_KEYS, "an edge label")
        for key in ("angle", "left", "right"):
            if key not in s:
                raise self.fail(f"edge label '{self.name(tok)}' has no {key}", tok,
                                "write: label x angle=0 left=inside right=exterior class=0")
        where = {self.name(r.children[0]): r.children[-1].children[0] for r in rest}
        angle = s["angle"]
        if not 0.0 <= angle < 180.0:
            raise self.fail(f"angle {angle:g} is outside [0, 180)", where["angle"],
                            "a label's angle is the direction of its half-edge x; ~x points "
                            "the opposite way, so use the angle modulo 180")
        for side in ("left", "right"):
            if s[side] not in faces:
                raise self.fail(f"unknown face label '{s[side]}'", where[side],
                                did_you_mean(s[side], faces) or "declare it in the 'faces' line")
        cls = s.get("class", DEFAULT_CLASS)
        if cls in self.broken and cls not in classes:
            raise _Stop()
        if cls not in classes:
            raise self.fail(f"unknown edge class '{cls}'", where["class"],
                            did_you_mean(cls, classes) or "declare it with a 'class' line")
        length, typical, shortest = s.get("length"), s.get("typical"), s.get("shortest")
        for key, value in (("length", length), ("typical", typical), ("shortest", shortest)):
            if value is not None and not value > 0:
                raise self.fail(f"the {key} must be positive", where[key])
        name = self.name(tok)
        if not name:
            raise self.fail("an edge label needs a name", tok)
        return EdgeLabel(name, s["left"], s["right"], angle, cls, length, typical, shortest)

    def _half(self, node: Tree, label_ids: dict[str, int]) -> tuple[int, Token]:
        bar = len(node.children) == 2
        tok = node.children[-1]
        lid = self.lookup("edge label", tok, label_ids, "declare it with a 'label' line")
        return bd.half(lid, bar), tok

    def _primitive(self, node: Tree, labels, label_ids: dict[str, int]) -> Primitive:
        tok, *rest = node.children
        halves = [self._half(n, label_ids) for n in rest if n.data == "half_edge"]
        s = self.settings([n for n in rest if n.data == "pair"], _PRIMITIVE_KEYS, "a primitive")
        ring = tuple(t for t, _ in halves)
        dirs = [labels[bd.label_of(t)].direction(bd.is_bar(t)) for t in ring]
        for k in range(1, len(ring)):
            if dirs[k] <= dirs[k - 1]:
                order = sorted(range(len(ring)), key=lambda i: dirs[i])
                names = [l.name for l in labels]
                fixed = bd.format_tokens([ring[i] for i in order], names, ascii=True)
                what = ("two half-edges point the same way" if dirs[k] == dirs[k - 1]
                        else "the ring is not in counter-clockwise order")
                shown = bd.format_tokens([ring[k]], [l.name for l in labels], ascii=True)
                raise self.fail(f"{what}: {shown} at {dirs[k]:g}° comes after "
                                f"{dirs[k - 1]:g}°", halves[k][1],
                                "list half-edges by direction from -180° up to 180°"
                                + (f": {fixed}" if dirs[k] != dirs[k - 1] else ""))
        count = s.get("count", 1)
        if count < 0:
            raise self.fail("count cannot be negative", tok)
        return Primitive(self.name(tok), ring, count)

    def _decoration(self, node: Tree, targets: dict[str, set[str]]) -> Decoration:
        kind_tok, target_node, *rest = node.children
        kind = self.name(kind_tok)
        if kind not in targets:
            raise self.fail(f"unknown decoration kind '{kind}'", kind_tok,
                            did_you_mean(kind, targets) or "face, edge or vertex")
        target_tok = target_node.children[0]
        target = "*" if target_tok.type == "STAR" else self.name(target_tok)
        if target != "*" and target not in targets[kind] and target in self.broken:
            raise _Stop()
        if target != "*" and target not in targets[kind]:
            what = {"face": "face label", "edge": "edge class", "vertex": "primitive"}[kind]
            raise self.fail(f"unknown {what} '{target}'", target_tok,
                            did_you_mean(target, targets[kind]) or "'*' decorates all of them")
        pairs = []
        for s in rest:
            key = self.name(s.children[0])
            if len(s.children) < 2:
                raise self.fail(f"'{key}' needs a value: {key}=…", s.children[0])
            pairs.append((key, self.prop(s.children[1]), self.span(s.children[0]),
                          self.span(s.children[1].children[0])))
        try:   # the .gg schema: what a .ggr decoration holds goes into SVG
            props = check_decoration(kind, pairs, Path(self.path).parent, self.text)
        except UserError as exc:
            first = exc.diagnostics[0]
            raise self.fail(first.message, first.span, first.hint) from None
        return Decoration(kind, target, tuple(props.items()), span=self.span(kind_tok))

    # -- rules --


_STATUS = {"complete": True, "limited": False, "unknown": None}
_OPTION_KEYS = {"angle_tolerance": "float", "snap_angle": "float", "merge_distance": "optfloat",
                "unit": "optfloat", "connected": "bool", "no_loops": "bool"}
_LIMIT_KEYS = {"generations": "int", "half_edges": "int", "graphs": "int", "seconds": "float"}
_CLASS_KEYS = {"min": "optfloat", "max": "optfloat", "fixed": "optfloat", "tile": "optfloat",
               "rigid": "bool", "border": "bool"}
_LABEL_KEYS = {"angle": "float", "left": "name", "right": "name", "class": "name",
               "length": "optfloat", "typical": "optfloat", "shortest": "optfloat"}
_PRIMITIVE_KEYS = {"count": "int"}
