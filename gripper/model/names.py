"""Names of the generated model's elements, for lookups by name."""

from __future__ import annotations

from dataclasses import dataclass

MODEL_NAME = "soft_gripper"


def finger_name(k: int) -> str:
    return f"f{k}"


def drive_name(k: int, pneumatic: bool) -> str:
    """Finger ``k``'s drive actuator: ``f{k}_chamber`` (pneumatic) or ``f{k}_servo`` (cable)."""
    return f"{finger_name(k)}_{'chamber' if pneumatic else 'servo'}"


@dataclass(frozen=True)
class FingerNames:
    """Names of one finger's elements in the model (for lookups by name)."""

    prefix: str
    n_segments: int
    pneumatic: bool = False

    @property
    def bodies(self) -> list[str]:
        return [f"{self.prefix}_seg{j}" for j in range(1, self.n_segments + 1)]

    @property
    def hinges(self) -> list[str]:
        """The hinges from the palm out: the cable finger's join elements 1-2 .. (n-1)-n; the
        pneumatic finger's start with ``hinge1``, its root at the clamp."""
        first = 1 if self.pneumatic else 2
        return [f"{self.prefix}_hinge{j}" for j in range(first, self.n_segments + 1)]

    @property
    def pads(self) -> list[str]:
        return [f"{self.prefix}_seg{j}_pad" for j in range(1, self.n_segments + 1)]

    cable = property(lambda self: f"{self.prefix}_cable")
    chamber = property(lambda self: f"{self.prefix}_chamber")
    # the finger's drive actuator: the servo that reels the cable in, or the chamber's regulator
    drive = property(lambda self: f"{self.prefix}_chamber" if self.pneumatic else f"{self.prefix}_servo")
    servo = property(lambda self: f"{self.prefix}_servo")
    reel = property(lambda self: f"{self.prefix}_reel")
    tip = property(lambda self: f"{self.prefix}_tip")
    mount = property(lambda self: f"{self.prefix}_mount")
