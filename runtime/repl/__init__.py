"""`ggrun --repl`: the session and its loop (`session`), the commands (`commands`) and tab
completion (`complete`)."""
