"""The package's version: one home, read by the package (``cable_ocp.__version__``), its
build (pyproject's dynamic version), the function cache's key and the batch store's meta
record. Below every layer: any module may import it."""

__version__ = "0.2.0"
