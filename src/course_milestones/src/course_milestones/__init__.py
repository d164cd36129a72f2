"""Course milestones: the list of milestones (registry) and the discovery helpers their checks use
to find what the texts leave open (executables, message fields, key maps)."""
