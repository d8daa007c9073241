"""The pneumatic finger's drive, in one place: the proportional regulator's datasheets and model
(``regulator``), the chamber actuator in the MJCF and the finger's segment chain (``chamber``), and
what the regulator reports (``sensing``). Each module sits on the layer of what it needs
(``.importlinter``): the datasheets below the parameters, the chamber beside the model builders,
the sensing beside the simulation.
"""
