"""One stable hash for configurations and designs: SHA-256 of canonical JSON."""

from __future__ import annotations

import hashlib
import json


def config_hash(*parts) -> str:
    """SHA-256 (first 16 hex digits) of the JSON of ``parts`` (sorted keys)."""
    blob = json.dumps(parts, sort_keys=True, default=str).encode()
    return hashlib.sha256(blob).hexdigest()[:16]
