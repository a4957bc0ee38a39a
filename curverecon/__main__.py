"""``python -m curverecon`` runs the command line."""

from curverecon.cli import main

raise SystemExit(main())
