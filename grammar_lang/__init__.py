"""The languages (.gg examples, .ggr rule files), their diagnostics, and the shared model of
labels, graphs, boundary strings and rules."""

__version__ = "0.1.0"
