"""The one exception type that user-caused errors raise."""

from __future__ import annotations


class CableOCPError(ValueError):
    """A problem file, an override or an API argument is invalid.

    The message names the offending key or value and says what would be valid.
    Solver failures are *not* raised: they come back as a solution whose ``status``
    is not ``"solved"``, with diagnostics.
    """
