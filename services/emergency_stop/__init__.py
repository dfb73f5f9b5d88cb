"""The emergency-stop band: a process of its own that latches the arm's stop at the hardware.

RT-CORBA gives a stop its own banded connection so it never queues behind other work; here the
band is a whole process. ProxyRobot's own EmergencyStop runs on its emergency lane, but the
request still goes through that process's gRPC transport and interpreter lock first, so 200
busy low-lane calls in it delay the stop by tens of ms (`make bench`: estop_under_load_proxy).
This process serves the same `ProxyRobot.EmergencyStop` contract on its own port
(TELEROBOT_EMERGENCY_STOP_ADDRESS, default 127.0.0.1:50055) and reaches the arm through the
EmergencyStopLink, past the driver. Every other ProxyRobot method answers UNIMPLEMENTED.

ProxyRobot sees the latch in its next state sample and reports ESTOPPED ("a latched stop was
set at the hardware"); Reset through ProxyRobot (or the DecisionServer) clears it, as ever.
"""
