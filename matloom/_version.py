"""MatLoom's version (level 0: any module may import it; ``matloom.__version__`` re-exports it)."""

__version__ = "0.1.0"
