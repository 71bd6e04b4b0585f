import sys

from plxtools.cli import main

sys.exit(main())
