"""``python -m lkspace``."""

import sys

from .cli import main

sys.exit(main())
