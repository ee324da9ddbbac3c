"""``python -m wheelrail``: the same command line as the ``wheelrail`` console script."""

import sys

from .cli.main import main

if __name__ == "__main__":
    sys.exit(main())
