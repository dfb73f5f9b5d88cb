"""Fakes of the ports, with honest physics, for in-process deterministic tests."""
