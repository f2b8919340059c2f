"""``python -m spinbounce``: the ``spinbounce`` command."""

import sys

from .cli import main

sys.exit(main())
