"""ABI hashes of the numba kernels: the source text their compiled code depends on.

numba keys a kernel in its on-disk cache on the source of the file that defines it (plus its
bytecode and the target), not on the files of the functions it calls or inlines, nor on the
module constants it freezes from other modules. Editing a callee in another file (an inline
helper of ``noise_numba_core``, the register machine, a channel slot constant) would leave a
cached caller that silently computes the old values.

So a kernel file's ABI hash covers the source of every MatLoom module in its *import closure*:
its module-level ``from matloom... import ...`` / ``import matloom...`` statements, followed
transitively within the package (a package's ``__init__`` only where a name is not a
submodule). :mod:`matloom.engine.kernels.jit` mixes :func:`file_hash` into numba's freshness
stamp of every kernel, so a stale cached kernel is recompiled, never used;
:mod:`matloom.runtime.warmup` puts :func:`kernels_hash` into its readiness stamp.

Only text is read (a regular expression over the imports, no parsing, no importing): a few
milliseconds for the whole package. Importing this module imports neither numba nor anything
else of MatLoom.
"""

from __future__ import annotations

import hashlib
import re
from functools import cache
from pathlib import Path

#: This copy's ``matloom/engine/kernels`` directory and the directory holding ``matloom``.
KERNELS = Path(__file__).resolve().parent
PACKAGE_ROOT = KERNELS.parents[2]
#: The module every numba kernel is decorated through (a file whose closure holds it is a
#: kernel module).
JIT_MODULE = KERNELS / "jit.py"

_IMPORT = re.compile(
    r"^(?:from[ \t]+(matloom(?:\.\w+)*)[ \t]+import[ \t]+(\([^)]*\)|[^\n]*)"
    r"|import[ \t]+(matloom(?:\.\w+)*))",
    re.MULTILINE,
)


def _module_file(name: str) -> Path | None:
    """The source file of module ``name`` in this copy of the package, if it has one."""
    base = PACKAGE_ROOT.joinpath(*name.split("."))
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def _imported_names(clause: str) -> list[str]:
    """The names of a ``from ... import`` clause (parentheses, aliases and comments dropped)."""
    text = re.sub(r"#[^\n]*", "", clause).strip().strip("()")
    return [item.split()[0] for item in text.split(",") if item.split()]


@cache
def _source(path: Path) -> bytes:
    return path.read_bytes()


@cache
def direct_imports(path: Path) -> tuple[Path, ...]:
    """The MatLoom source files that ``path`` imports at module level (column 0)."""
    found: list[Path] = []
    for match in _IMPORT.finditer(_source(path).decode("utf-8", errors="replace")):
        module = match.group(1) or match.group(3)
        own = _module_file(module)
        if match.group(3) is not None or (own is not None and own.name != "__init__.py"):
            found.extend([own] if own is not None else [])
            continue
        # a package (or a namespace package, without __init__): names may be submodules
        subs = [_module_file(f"{module}.{name}") for name in _imported_names(match.group(2))]
        found.extend(sub for sub in subs if sub is not None)
        if own is not None and any(sub is None for sub in subs):  # a name of the __init__
            found.append(own)
    return tuple(dict.fromkeys(found))


@cache
def closure(path: Path) -> tuple[Path, ...]:
    """``path`` and every MatLoom source file it imports, transitively, sorted."""
    seen = {path.resolve()}
    todo = [path.resolve()]
    while todo:
        for dep in direct_imports(todo.pop()):
            if dep not in seen:
                seen.add(dep)
                todo.append(dep)
    return tuple(sorted(seen))


def _digest(paths: tuple[Path, ...] | list[Path]) -> str:
    h = hashlib.sha256()
    for p in sorted(paths):
        name = p.relative_to(PACKAGE_ROOT).as_posix() if p.is_relative_to(PACKAGE_ROOT) else p.name
        h.update(name.encode())
        h.update(hashlib.sha256(_source(p)).digest())
    return h.hexdigest()[:32]


@cache
def file_hash(path: str | Path) -> str:
    """The ABI hash of the kernels defined in ``path``: its import closure's source."""
    return _digest(closure(Path(path).resolve()))


def kernel_modules() -> list[Path]:
    """The kernel modules: files of this kernels package whose closure holds :data:`JIT_MODULE`
    (every numba kernel is decorated through it)."""
    return [p for p in sorted(KERNELS.glob("*.py")) if JIT_MODULE in closure(p.resolve())]


@cache
def kernels_hash() -> str:
    """The ABI hash of all kernel modules together (the union of their closures)."""
    files: set[Path] = set()
    for module in kernel_modules():
        files.update(closure(module.resolve()))
    return _digest(sorted(files))
