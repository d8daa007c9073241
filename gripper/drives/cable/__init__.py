"""The cable drive (:class:`gripper.drives.cable.drive.CableDrive`): the cut finger's geometry
(``geometry``) and closed cuts (``closure``), its MJCF with the cable and reel (``finger``), the
servo's actuator (``servo``), what the servo reports (``sensing``), the grip controller
(``controller``) and the bench check of the servo against its datasheet (``datasheet_check``).
The datasheets themselves are data, below the parameters: :mod:`gripper.datasheets.servo`."""
