"""The Python API's errors, in a module of their own so that the API's helper modules
(api_place, api_inspect) can raise them without importing the API back."""

from __future__ import annotations


class PlxApiError(Exception):
    """Base of the API's errors."""


class ModelError(PlxApiError):
    """The model cannot be simulated: ``diagnostics`` holds the located findings (errors first)."""

    def __init__(self, message: str, diagnostics: list | None = None):
        super().__init__(message)
        self.diagnostics = diagnostics or []


class SignalPathError(PlxApiError, KeyError):
    """No object with that dotted path; ``suggestion`` is the nearest existing one, if any."""

    def __init__(self, message: str, suggestion: str | None = None):
        super().__init__(message)
        self.message = message
        self.suggestion = suggestion

    def __str__(self) -> str:  # KeyError would quote the message
        return self.message


class NotSimulatedError(PlxApiError):
    """The signal exists but the MuJoCo backend does not map it (the message says why)."""
