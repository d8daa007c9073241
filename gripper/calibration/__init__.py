"""Calibration layer: the flexible-multibody reference finger and the hinge-stiffness fit."""
