"""Actuator datasheets, as data with their sources: the servos (``servo``) and the pressure
regulators (``regulator``). The bottom floor of the package, so that the parameters can validate
against them; each drive reads its own (``Drive.datasheet``)."""
