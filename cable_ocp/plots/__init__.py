"""Figures (matplotlib, Agg canvas: files only, nothing is shown on screen).

statics  cable profiles (side elevation, or 3D view, plan and elevation) with the tension
         along the cable; parameter sweeps; footprints
heave    heave-compensation comparisons (spectra, time series, running RMS, limits,
         trade-off curves)
bench    the work-precision diagram
common   the shared style: constrained layout, legends below the panels, units as "x (m)"

Every plotting function saves its figure and returns the matplotlib ``Figure``.
Part of the face of the package: library modules never import it.
"""
