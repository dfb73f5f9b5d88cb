"""The web console: a browser's door to the station (issue #18).

A gateway process that serves the console's page and speaks the contracts to the browser:
the Connect protocol (``connect-python``) for unary calls and server streams, a WebSocket
carrying binary ``TeleoperateRequest``/``TeleoperateResponse`` messages for the bidirectional
``Teleoperate``, and one carrying the video stream's ``ReportReceiptRequest`` messages
(receipts.py: over HTTP/1.1 the browser would queue them). It forwards each call to the
DecisionServer as a gRPC client, with the browser's lease, lane and bearer token as the call's
metadata, so the DecisionServer's own locks, roles, watchdog and audit apply to the browser as
to any client.
"""
