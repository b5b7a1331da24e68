"""The noncircular_gears drive: an output shaft carrying two identical non-circular driving
gears, each meshing externally with a driven non-circular gear fixed to one of two coaxial
rotors (twin-rotor engines, vane pumps); the second driving gear is turned on the shaft by an
installation phase, so the two rotors run with periodically varying speeds in antiphase and
the angle between them swings. The pitch curves are Litvin's n-lobed "modified ellipses"
about a rotation centre (an ellipse about a focus for one lobe) and their conjugates; the
kinematics, with its closed forms, is in :mod:`.kinematics`.
"""
