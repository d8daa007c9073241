"""One stable hash for configurations, designs and settings.

:func:`stable_hash` is SHA-256 of the value's canonical JSON (sorted keys, no whitespace
choices left to the caller), cut to 16 hex digits: the same value gives the same hash in every
process, on every machine and in every version of this package. Values that JSON cannot
represent are written with ``str``.
"""

from __future__ import annotations

import hashlib
import json
from typing import Any


def stable_hash(value: Any) -> str:
    """SHA-256 (first 16 hex digits) of ``value``'s JSON with sorted keys.

    Example:
        >>> stable_hash({"b": 1, "a": [1.5, "x"]}) == stable_hash({"a": [1.5, "x"], "b": 1})
        True
    """
    blob = json.dumps(value, sort_keys=True, default=str).encode()
    return hashlib.sha256(blob).hexdigest()[:16]
