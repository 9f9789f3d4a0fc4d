"""The stability analyses of systems in the horizontal plane (ships on turrets and hawsers):
the vector field (``plane``), every equilibrium and its stability (``equilibria``)."""
