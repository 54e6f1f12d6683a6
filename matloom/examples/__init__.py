"""Example programs shipped with MatLoom (the paper's two programs and the quick-start bricks)."""

from __future__ import annotations

from importlib import resources

NAMES = ("black_ceramic_tiles", "weathered_brick", "bricks_quickstart")


def example_text(name: str) -> str:
    """Source text of a shipped example program."""
    if name not in NAMES:
        raise KeyError(f"unknown example {name!r}; available: {', '.join(NAMES)}")
    return resources.files(__package__).joinpath(f"{name}.mat").read_text(encoding="utf-8")
