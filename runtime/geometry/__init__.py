"""Where vertices go: the placement solver (`solver`: edge-direction equations, rejection
sampling), the spatial grid (`spatial`), faces found from positions (`faces`), where a
free-standing component lands (`landing`) and the frame a scene is drawn in (`framing`)."""
