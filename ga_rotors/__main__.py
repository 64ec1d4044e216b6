"""``python -m ga_rotors``: the ``ga-rotors`` command."""

import sys

from .cli import main

sys.exit(main())
