"""``python -m cable_ocp`` is the same as the ``cable-ocp`` command."""

from cable_ocp.cli import main

raise SystemExit(main())
