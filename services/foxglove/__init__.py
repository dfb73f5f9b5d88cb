"""Foxglove's view of the station: our messages in Foxglove's schemas (`channels`), written into
`make teleop --mcap` recordings and served live."""
