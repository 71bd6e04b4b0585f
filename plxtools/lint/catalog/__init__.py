"""Rule catalogues, one module per stage; importing this package registers every rule."""

from plxtools.lint.catalog import hygiene, syntax  # noqa: F401

try:  # later stages register their own rules when present
    from plxtools.lint.catalog import semantic  # noqa: F401
except ImportError:  # pragma: no cover - only while a stage is being built
    pass
try:
    from plxtools.lint.catalog import assembly  # noqa: F401
except ImportError:  # pragma: no cover
    pass
