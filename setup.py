"""Build hook for the optional C speed-up ``matloom.engine.kernels._cnoise``.

All project metadata lives in pyproject.toml; this file only declares the extension.  It is
``optional=True``: without a working C compiler the install still succeeds and MatLoom uses the
pure-numpy fBm (same numbers, slower).  The flags forbid FMA contraction and fast-math, which
would change the last bits of the noise; no -march=native, so wheels run on any x86-64/aarch64.
"""

from __future__ import annotations

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

GCC_LIKE_FLAGS = ["-O3", "-ffp-contract=off", "-fno-fast-math", "-fno-trapping-math"]
MSVC_FLAGS = ["/O2", "/fp:precise"]


class BuildExtWithFlags(build_ext):
    """Pick the compiler flags by compiler family (MSVC spells them differently)."""

    def build_extensions(self) -> None:
        flags = MSVC_FLAGS if self.compiler.compiler_type == "msvc" else GCC_LIKE_FLAGS
        for ext in self.extensions:
            ext.extra_compile_args = list(flags)
        super().build_extensions()


setup(
    ext_modules=[
        Extension(
            "matloom.engine.kernels._cnoise",
            ["matloom/engine/kernels/_cnoise.c"],
            optional=True,
            extra_compile_args=GCC_LIKE_FLAGS,
        )
    ],
    cmdclass={"build_ext": BuildExtWithFlags},
)
