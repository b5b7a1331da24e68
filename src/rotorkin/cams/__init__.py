"""Cam geometry: manufacturable profiles and their checks.

* :mod:`rotorkin.cams.planar` - generic planar cam geometry on arrays (offsets,
  curvature, pressure angle, undercut, chordal resampling);
* :mod:`rotorkin.drives.rhomboid_cam.cam` - the rhomboid cam and its four rollers;
* :mod:`rotorkin.drives.eccentric_cam.cam` - the two eccentric discs;
* :mod:`rotorkin.drives.guide_bar.cam` - the impeller outlines of the guide-bar vane pump;
* :mod:`rotorkin.drives.wobble_cam.cam` - the spherical cam of the wobble-cam drive.

Submodules are imported on demand (``from rotorkin.cams import rhomboid``).
"""
