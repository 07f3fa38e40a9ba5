"""Shared .gg modules that `import` finds by name."""
