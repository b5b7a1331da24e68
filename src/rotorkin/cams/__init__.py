"""Cam geometry: manufacturable profiles and their checks.

* :mod:`rotorkin.cams.planar` - generic planar cam geometry on arrays (offsets,
  curvature, pressure angle, undercut, chordal resampling);
* :mod:`rotorkin.cams.rhomboid` - the rhomboid cam and its four rollers;
* :mod:`rotorkin.cams.eccentric` - the two eccentric discs;
* :mod:`rotorkin.cams.impeller` - the impeller outlines of the guide-bar vane pump;
* :mod:`rotorkin.cams.spherical` - the spherical cam of the wobble-cam drive.

Submodules are imported on demand (``from rotorkin.cams import rhomboid``).
"""
