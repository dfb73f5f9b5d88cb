"""The Python side of the contracts, shared by services and clients.

Only the standard library, numpy, protobuf and the generated ``telerobot.v1`` code: an
operator's client needs nothing of the slave station (no Pinocchio, MuJoCo or OpenCV; OpenCV is
imported only when a JPEG or PNG frame is decoded).

* ``errors``    -- the domain errors, one per gRPC status code, without grpc
* ``checks``    -- incoming values: finite vectors, rotation matrices (Gram-Schmidt)
* ``pose``      -- `Pose`, a rigid transform as a rotation matrix and a translation
* ``convert``   -- protos <-> numpy values, poses, timestamps and durations
* ``metadata``  -- the metadata keys (lane, lease) and the lane names
* ``addresses`` -- default ports, ``TELEROBOT_<SERVICE>_ADDRESS``, `address_for`
* ``stereo``    -- StereoCamera channel options and frame decoding
"""
