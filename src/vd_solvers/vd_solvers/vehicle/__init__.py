"""
The full-vehicle rung: Pinocchio multibody car, suspension maps from K&C, Magic Formula
tires, drivers, the constant radius turn and the step steer (ROS-free; see docs/models.md).
"""
