"""The `blender` marker: tests that need Blender or the bpy module (skipped without them)."""

from __future__ import annotations

import pytest


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers", "blender: needs Blender 4.2+ or the bpy module (make blender-venv)"
    )
