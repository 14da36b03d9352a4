"""``python -m flutterfriction ...``: the same command line as the ``flutterfriction`` script."""

import sys

from flutterfriction.cli import main

sys.exit(main())
