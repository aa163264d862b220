"""Grasp planning and MuJoCo grasp validation."""
