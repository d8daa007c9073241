"""The gripper's assembly (``builders``): the palm on its lift stage, one finger per mount built by
the gripper's drive (:mod:`gripper.drives`), and the scene around it."""
