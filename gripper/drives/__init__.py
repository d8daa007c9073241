"""The drives: each kind of finger with what bends it, one folder each (``cable``, ``pneumatic``),
behind one interface (:class:`gripper.drives.drive.Drive`, chosen by ``actuation.kind``)."""

from gripper.drives.drive import Drive, drive_class, drive_for, register_drive, unregister_drive

__all__ = ["Drive", "drive_class", "drive_for", "register_drive", "unregister_drive"]
