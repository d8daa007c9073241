"""The pneumatic drive (:class:`gripper.drives.pneumatic.drive.PneumaticDrive`): the segment
chain and its chamber actuator in the MJCF (``chamber``), what the regulator reports
(``sensing``) and the ramp-and-hold controller (``controller``). The regulators' datasheets are
data, below the parameters: :mod:`gripper.datasheets.regulator`."""
