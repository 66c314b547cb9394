"""``python -m kitchen_tamp.evaluate``: see ``kitchen_tamp.evaluate.command_line``."""

import sys

from kitchen_tamp.evaluate.command_line import main

if __name__ == "__main__":
    sys.exit(main())
