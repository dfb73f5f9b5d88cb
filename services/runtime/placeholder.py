"""A service process whose servicers are not built yet (see unimplemented.py)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from services.runtime.server import ServiceBinding


@dataclass
class PlaceholderService:
    """Serves its bindings; has nothing to start or release."""

    served: Sequence[ServiceBinding]

    def bindings(self) -> Sequence[ServiceBinding]:
        return self.served

    def start(self) -> None:
        pass

    def close(self) -> None:
        pass
