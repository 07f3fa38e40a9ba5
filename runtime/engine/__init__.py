"""The rewriting engine: the host drawing and its indexes (`host`), anchored matching of rule
sides (`matching`), DPO/SPO rewriting (`rewrite`), rule choice (`schedule`), the costs that
steer it (`costs`), the loop that runs it all (`generate`) and each move's record of
whether its late rounds pay (`late`); `free_host`, `free_match`,
`free_engine` run hand-written productions. The engine stands on runtime.geometry, which
places each change and never imports the engine."""
