"""The station's Zenoh router (wire/observation.py): observers subscribe through it."""
