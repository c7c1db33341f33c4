"""``python -m moving_bogie`` runs the command line interface."""

import sys

from moving_bogie.cli import main

sys.exit(main())
