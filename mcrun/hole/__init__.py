"""A real golf hole under the shots: the course map (``osm``), the hole's metric frame
(``geo``), its turf zones (``zones``) and the hole itself with its ground grid (``hole``);
elevation files (``elevation``) and analytic ground shapes (``shapes``) give its heights."""
