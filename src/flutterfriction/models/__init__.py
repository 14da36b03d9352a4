"""Mechanical systems as data plus their matrices and equations of motion (no solving here)."""

from flutterfriction.models.ziegler import PendulumGroups, ZieglerPendulum

__all__ = ["PendulumGroups", "ZieglerPendulum"]
