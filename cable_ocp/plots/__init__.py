"""Figures (matplotlib, Agg canvas: files only, nothing is shown on screen).

Modules
-------
statics         cable profiles (side elevation, or 3D view, plan and elevation) with the
                tension along the cable
statics_series  parameter sweeps; footprints
dynamics        simulations, mode shapes, the deployment resonance chart
deploy          the optimal pay-out schedule: length with the resonant lengths, speed,
                the tension envelope, power
heave           heave-compensation comparisons (spectra, time series, running RMS, limits,
                trade-off curves); heave_cable the deployment through resonance
system          mooring systems: plan and 3D views coloured by tension, the offset curve
batch           an output of a load-case batch over its swept keys
response        frequency-response curves: amplitude ratio against frequency, linear and
                time runs, natural frequencies marked
bench           the work-precision diagrams
accessors       the results' ``.plot(ax=None)`` methods
common          the shared style: constrained layout, legends below the panels, units as "x (m)"

Every ``plot_*`` function saves its figure and returns the matplotlib ``Figure``; the
``*_figure`` functions build it without saving. Part of the face of the package: library
modules never import it (a result's ``plot`` method imports :mod:`.accessors` when called).
"""
