"""The station's observation, published once into Zenoh (wire/observation.py)."""
