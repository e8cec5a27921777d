"""lgw.sim.lunar: seed 001's plant (polar translational dynamics, quaternion attitude),
actuators (thrust saturation (24), failure (26), torque saturation (28)), the generated law,
the reference trajectory (3)-(4) and the batched simulator."""
