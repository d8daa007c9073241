"""What every finger's model shares, whatever drives it: element names (``names``), default
classes, materials and options (``defaults``), compliant contact pads (``pads``) and the hinge
chain of a uniform beam (``beam``)."""
