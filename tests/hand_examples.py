"""Examples given by their primitives, as the paper's figures give them."""

from grammar_lang.example import Example
from grammar_lang.vocabulary import EdgeLabel, Primitive, Vocabulary
from grammar_lang.source import EdgeClass, Options

X, XB, Y, YB = 0, 1, 2, 3     # tokens of labels x (0°) and y (90°)

# Fig. 5: the rectangle's four corners, by angle: ȳx∧ (top left), xy∧ (bottom left),
# x̄y∧ (bottom right), x̄ȳ∧ (top right).
RECTANGLE = [(YB, X), (X, Y), (XB, Y), (XB, YB)]
# §5.5: corners and a T junction (x̄ȳx∧): loops only, no primitive is a stub.
CORNERS_AND_T = RECTANGLE + [(XB, YB, X)]


def make(rings, labels=(("x", 0.0), ("y", 90.0)), options=Options(), name="hand") -> Example:
    labs = tuple(EdgeLabel(n, "exterior", "exterior", a, "0") for n, a in labels)
    prims = tuple(Primitive(f"p{k}", tuple(r)) for k, r in enumerate(rings))
    vocabulary = Vocabulary("exterior", ("exterior",), (EdgeClass("0", 10.0, 400.0),), labs,
                            prims, 100.0)
    return Example(name=name, path="<hand>", vocabulary=vocabulary, options=options)
