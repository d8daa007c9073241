"""Names of the generated model's elements, for lookups by name."""

from __future__ import annotations

from dataclasses import dataclass

MODEL_NAME = "soft_gripper"


def finger_name(k: int) -> str:
    return f"f{k}"


@dataclass(frozen=True)
class FingerNames:
    """Names of one finger's elements in the model (for lookups by name)."""

    prefix: str
    n_segments: int

    @property
    def bodies(self) -> list[str]:
        return [f"{self.prefix}_seg{j}" for j in range(1, self.n_segments + 1)]

    @property
    def hinges(self) -> list[str]:
        return [f"{self.prefix}_hinge{j}" for j in range(2, self.n_segments + 1)]

    @property
    def pads(self) -> list[str]:
        return [f"{self.prefix}_seg{j}_pad" for j in range(1, self.n_segments + 1)]

    cable = property(lambda self: f"{self.prefix}_cable")
    servo = property(lambda self: f"{self.prefix}_servo")
    reel = property(lambda self: f"{self.prefix}_reel")
    tip = property(lambda self: f"{self.prefix}_tip")
    mount = property(lambda self: f"{self.prefix}_mount")
