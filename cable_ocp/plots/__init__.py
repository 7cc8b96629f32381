"""Figures (matplotlib, Agg backend: files only, nothing is shown on screen).

statics  cable profiles, sweeps and footprints
heave    heave-compensation comparisons (spectra, time series, trade-off curves)

Part of the face of the package: library modules never import it.
"""
