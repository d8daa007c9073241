"""Servo-motor datasheets and the controller gains derived from them.

A servo here is a DC motor with a gearbox and an on-board position controller. MuJoCo's
``dcmotor`` actuator models it at the output shaft: ``nominal = (voltage, stall torque, no-load
speed)`` fixes the motor constant and the winding resistance, the on-board PID acts in torque
space and its drive voltage is clamped to the supply voltage, and the rotor inertia reflected
through the gearbox is the actuator ``armature``.

Example:
    >>> from gripper.datasheets.servo import servo_datasheet
    >>> round(servo_datasheet("hobby_6v").stall_torque, 3)
    1.079
"""

from __future__ import annotations

import math
from dataclasses import dataclass

KGF_CM = 9.80665e-2  # N·m per kgf·cm (standard gravity 9.80665 m/s²)


@dataclass(frozen=True)
class ServoDatasheet:
    """One servo model's datasheet figures, all at the output shaft (SI units).

    Attributes:
        name: preset key.
        description: the product class the figures come from.
        voltage: supply voltage the figures hold at [V].
        stall_torque: stall torque [N·m].
        no_load_speed: no-load output speed [rad/s].
        step_60deg_time: datasheet time for a 60° move with no load [s].
        rotor_inertia: rotor inertia reflected to the output shaft, J_rotor · N² [kg·m²].
        travel: mechanical travel of the output shaft [rad].
        source: where each figure comes from.
    """

    name: str
    description: str
    voltage: float
    stall_torque: float
    no_load_speed: float
    step_60deg_time: float
    rotor_inertia: float
    travel: float
    source: str

    def pd_gains(self, *, saturation_error: float, damping_ratio: float) -> tuple[float, float]:
        """Torque-space PD gains of the on-board controller.

        ``kp`` makes the controller ask for the full stall torque at ``saturation_error`` [rad]
        (hobby-servo dead bands are about 0.5-1°, so the motor stays saturated until it is that
        close); ``kd`` gives the reflected rotor inertia the requested damping ratio,
        ``kd = 2 ζ sqrt(kp J)`` (the dcmotor controller compensates back-EMF, so only ``kd``
        damps the loop).
        """
        kp = self.stall_torque / saturation_error
        kd = 2.0 * damping_ratio * math.sqrt(kp * self.rotor_inertia)
        return kp, kd


# Hobby servo, MG996R class (the metal-gear 6 V servo common in hobby grippers).
# Datasheet (TowerPro MG996R): stall torque 11 kgf·cm at 6 V, operating speed 0.14 s/60° at 6 V,
# no load. Hobby-servo datasheets give speed only as the 60° transit time, so the no-load speed is
# read from it: (π/3) / 0.14 s = 7.48 rad/s.
# Rotor inertia is not on the datasheet: a 130-size can motor rotor (≈ 5 g, Ø 12 mm,
# J ≈ ½ m r² ≈ 9e-8 kg·m²) behind a ≈ 1:98 gearbox (motor no-load ≈ 7000 rpm / 7.48 rad/s)
# gives J ≈ 9e-8 · 98² ≈ 8.6e-4 kg·m² at the output: an estimate, written down as such.
_HOBBY = ServoDatasheet(
    name="hobby_6v",
    description="6 V metal-gear hobby servo (MG996R class)",
    voltage=6.0,
    stall_torque=11.0 * KGF_CM,
    no_load_speed=(math.pi / 3.0) / 0.14,
    step_60deg_time=0.14,
    rotor_inertia=8.6e-4,
    travel=math.pi,  # 180° hobby servo travel
    source="TowerPro MG996R datasheet (6 V: 11 kgf·cm, 0.14 s/60°); rotor inertia estimated",
)

# Smart servo, Dynamixel XL430-W250-T at 12 V.
# Datasheet (ROBOTIS e-Manual, XL430-W250): stall torque 1.5 N·m at 12 V, no-load speed 61 rpm
# at 12 V, gear ratio 258.5:1, multi-turn mode ±256 rev (we allow four turns of cable spool).
# The datasheet gives no 60° time; it is derived as (π/3) / no-load speed (marked derived).
# Rotor inertia estimated: coreless-class rotor ≈ 1.5e-8 kg·m² × 258.5² ≈ 1.0e-3 kg·m².
_SMART = ServoDatasheet(
    name="smart_12v",
    description="12 V smart servo (Dynamixel XL430-W250 class), multi-turn mode",
    voltage=12.0,
    stall_torque=1.5,
    no_load_speed=61.0 * 2.0 * math.pi / 60.0,
    step_60deg_time=(math.pi / 3.0) / (61.0 * 2.0 * math.pi / 60.0),
    rotor_inertia=1.0e-3,
    travel=4.0 * 2.0 * math.pi,
    source="ROBOTIS XL430-W250 e-Manual (12 V: 1.5 N·m, 61 rpm, 258.5:1); "
    "60° time derived; rotor inertia estimated",
)

SERVO_PRESETS: dict[str, ServoDatasheet] = {s.name: s for s in (_HOBBY, _SMART)}


def servo_datasheet(name: str) -> ServoDatasheet:
    """The datasheet of preset ``name``.

    Raises:
        ValueError: ``name`` is not a known preset.
    """
    try:
        return SERVO_PRESETS[name]
    except KeyError:
        allowed = ", ".join(sorted(SERVO_PRESETS))
        raise ValueError(f"servo.preset: unknown servo preset {name!r}; allowed: {allowed}") from None
