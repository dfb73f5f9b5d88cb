"""The world process: the simulated PUMA 560 and wrist sensor that stand in for the hardware.

link.py      the hardware-link protocols (ArmLink, WrenchLink) drivers program against
sim.py       the MuJoCo arm and its joint servo (trajectory.py: the rate-limited reference)
realtime.py  the 1 kHz loop with overrun accounting
shm_*.py     the shared-memory link (seqlock.py: torn-free records)
service.py   the three together as a service; `python -m services.world` runs it
measure.py   link latency from a driver process
"""
