"""Fakes of the ports the cores talk through: a few lines of honest physics on a fake clock."""
