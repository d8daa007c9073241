"""One module per ``gripper`` command: ``add(sub)`` declares its options, ``run(args)`` runs it.

The command line's order: :data:`COMMANDS`.
"""

COMMANDS = ("bend", "servo", "params", "write_models", "check", "bench", "video", "study", "envelope",
            "calibrate", "pullout", "crush", "train", "play")
