"""Compiled kernels that load on first use, and the loops they share."""
