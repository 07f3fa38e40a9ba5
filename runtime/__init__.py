"""Generation: rewriting, geometry, output, the verifier and the REPL (Merrell 2023, §6)."""
