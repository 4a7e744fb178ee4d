"""The kernel: the shot's event loop (fly, land, bounce, roll) over the physics, the schemas of
its inputs and outcomes, and the one function that runs a batch of shots."""
