"""One-off studies behind numbers in docs/ (mimicry table, instruction split, microgeometry
checks, the fit showcase); run from a checkout with the .venv's Python."""
