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
    #: index of the first hinge from the palm: 2 when element 1 is fixed to the palm (the cable
    #: finger), 1 when the first segment sits on a root hinge at the clamp (the pneumatic finger)
    first_hinge: int = 2
    #: suffix of the finger's drive actuator (``servo``, ``chamber``, ...)
    actuator: str = "servo"

    # element j's (1-based) names: its body, geoms, touch site, pad and cable site
    def body(self, j: int) -> str:
        return f"{self.prefix}_seg{j}"

    def visual(self, j: int) -> str:
        return f"{self.body(j)}_visual"

    def collision(self, j: int) -> str:
        return f"{self.body(j)}_collision"

    def pad(self, j: int) -> str:
        """The touch site on element j's grasping face."""
        return f"{self.body(j)}_pad"

    def pad_body(self, j: int) -> str:
        return f"{self.body(j)}_padbody"

    def pad_slide(self, j: int) -> str:
        return f"{self.body(j)}_padslide"

    def pad_collision(self, j: int) -> str:
        return f"{self.body(j)}_pad_collision"

    def cable_site(self, j: int) -> str:
        """The cable's via point in element j's hole."""
        return f"{self.body(j)}_cable"

    def hinge(self, j: int) -> str:
        """The hinge that carries element j (``hinge{j}``)."""
        return f"{self.prefix}_hinge{j}"

    @property
    def bodies(self) -> list[str]:
        return [self.body(j) for j in range(1, self.n_segments + 1)]

    @property
    def hinges(self) -> list[str]:
        """The hinges from the palm out, ``hinge{first_hinge}`` .. ``hinge{n_segments}``: the cable
        finger's join elements 1-2 .. (n-1)-n; the pneumatic finger's start with ``hinge1``, its
        root at the clamp."""
        return [self.hinge(j) for j in range(self.first_hinge, self.n_segments + 1)]

    @property
    def pads(self) -> list[str]:
        return [self.pad(j) for j in range(1, self.n_segments + 1)]

    cable = property(lambda self: f"{self.prefix}_cable")
    chamber = property(lambda self: f"{self.prefix}_chamber")
    # the finger's drive actuator: the servo that reels the cable in, the chamber's regulator, ...
    drive = property(lambda self: f"{self.prefix}_{self.actuator}")
    servo = property(lambda self: f"{self.prefix}_servo")
    reel = property(lambda self: f"{self.prefix}_reel")
    tip = property(lambda self: f"{self.prefix}_tip")
    tip_anchor = property(lambda self: f"{self.prefix}_tip_anchor")
    cable_guide = property(lambda self: f"{self.prefix}_cable_guide")
    reel_site = property(lambda self: f"{self.prefix}_reel_site")
    mount = property(lambda self: f"{self.prefix}_mount")
