"""Helpers for the milestone rostests: start the node under test, drive it through a
pseudo-terminal, wait for conditions, read what nodes log."""
