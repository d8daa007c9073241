"""The servo that reels in each cable, in one place: its datasheets (``datasheet``), its MJCF
actuator (``actuator``), what it reports as a smart servo does (``sensing``) and the bench check
of the model against its datasheet (``datasheet_check``). Each module sits on the layer of what
it needs (``.importlinter``): the datasheets below the parameters, the actuator beside the model
builders, the sensing beside the simulation, the check beside the experiments.
"""
