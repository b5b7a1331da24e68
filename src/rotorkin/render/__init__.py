"""Shared drawing and CAD helpers: matplotlib figures, plotly scenes, CAD files of planar parts.

Every drive's figures, report scene and CAD build on these; none of them names a drive.
"""
