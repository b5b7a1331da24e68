"""Cam geometry: manufacturable profiles and their checks.

* :mod:`rotorkin.cams.planar` - generic planar cam geometry on arrays (offsets,
  curvature, pressure angle, undercut, chordal resampling).

Each drive's own cam (plates, discs, grooves) lives in its package,
``rotorkin/drives/<name>/cam.py``, built on this one.
"""
