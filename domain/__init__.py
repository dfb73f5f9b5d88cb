"""The robot domain both stations share: the arm's model and kinematics, passivity, geometry.

No grpc here, and no generated code: these are numbers in, numbers out."""
