"""The milestones of each course text, one module per text (000-004)."""
