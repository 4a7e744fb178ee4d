"""``python -m benchmarks [--quick] [--huge] [--out DIR] [--only FIGURES]``: see suite.py."""

import sys

from benchmarks.suite import main

sys.exit(main())
