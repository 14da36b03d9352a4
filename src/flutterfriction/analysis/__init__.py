"""Numerical solvers that work on any model given by its matrices."""
