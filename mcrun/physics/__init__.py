"""The physics of a shot, each formula once, in SI: the ball and the air (``constants``,
``atmosphere``), the launch from the club (``launch``), the aerodynamic models (``aero``), the
flight's forces and step (``flight``), Penner's bounce on compliant turf (``bounce``), the slide
and roll (``roll``) and the turf (``turf``). Nothing here knows of shots in bulk, files or the
command line; it imports only ``mcrun.status`` and ``mcrun.trajectory`` from outside."""
