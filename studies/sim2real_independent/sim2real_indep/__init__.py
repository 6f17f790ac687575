"""Modules of the independent sim-to-real benchmark (a package, so that their names cannot clash with other
studies' modules on the test path). Nothing here imports tolalloc."""
