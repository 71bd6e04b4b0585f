"""The "did you mean" of an unknown name: a help line and an unsafe fix that writes the name the
model found closest (the model finds it; this says it)."""

from __future__ import annotations

from plxtools.diagnostics import Edit, Fix, Span


def did_you_mean(span: Span, word: str | None) -> tuple[str | None, Fix | None]:
    """(help, fix) replacing the text at `span` with `word`; (None, None) without a word."""
    if word is None:
        return None, None
    return f"did you mean '{word}'?", Fix(f"replace with '{word}'", (Edit(span.start.offset, span.end.offset, word),),
                                          safe=False)
