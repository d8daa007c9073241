"""The slow reference models that the fast hinge-chain gripper is calibrated or checked against,
apart from the fitting code (:mod:`gripper.calibration`):

- ``continuum``: the silicone finger as a MuJoCo 3D flex bent by its cable, with its mesh
  (``finger_mesh``), its mesh-convergence study (``convergence``), checks against closed forms
  (``continuum_checks``) and its static points relaxed to rest (``relaxation``);
- ``fmbs``: paper 000's own flexible multibody model of the finger;
- ``yeoh_tube``: the Yeoh thick-walled tube, exact and by FElupe, the first check of paper 001's
  pneumatic actuator model;
- paper 001's actuator: its parameters (``pneumatic_params``), mesh (``actuator_mesh``), fibre
  (``fibre_materials``), finite-element sweep (``actuator_fe``), its duct's deformed section
  (``actuator_section``), the semi-analytical moment balance (``bending_moment_model``) and the
  pneumatic finger's calibration reference (``actuator_bending``).
"""
