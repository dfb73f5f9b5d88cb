"""The arms: their description files, kinematics, dynamics and IK.

Pure domain code (no transport). Modules, one job each (import them directly: this package
imports nothing, so a process that needs only an arm's name loads neither MuJoCo nor Pinocchio):

* ``description`` -- an arm as its file declares it, checked; which arm this station drives
* ``names``       -- the element names every arm file uses (sites, sensors, home keyframe)
* ``puma560``, ``fr3``, ``ur5e`` -- each arm's numbers (``serial_chain`` for the last two)
* ``workspace``   -- the work cell around an arm (table, peg-in-hole fixture, stereo cameras)
* ``mjcf``        -- writes each arm's ``arms/<arm>/arm.xml`` and ``scene.xml`` from the above
* ``loader``      -- loads the MuJoCo / Pinocchio models and resolves MuJoCo ids by name
* ``kinematics``  -- ``ArmKinematics``: poses, Jacobians, D(q), C(q, qd), G(q), RNEA
* ``ik``          -- damped least-squares inverse kinematics within the joint limits
* ``singularity`` -- distance-to-singularity measures for Cartesian motion
"""
