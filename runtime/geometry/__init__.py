"""Where vertices go: the placement solver (`solver`: edge-direction equations, rejection
sampling; `pinv`: its systems' pseudo-inverse), the spatial grid (`spatial`), faces found
from positions (`faces`), where a free-standing component lands (`landing`) and the frame a
scene is drawn in (`framing`).

The geometry is the layer below the engine and imports nothing from it. What the two share
lives here: the per-slot tables (`tables`), the change to place and the host as the geometry
sees it (`change`), and why a proposal was refused (`rejections`)."""
