"""The course's JupyterHub: the class list, the spawner's settings, grading from the hub (docs/hub.md)."""
