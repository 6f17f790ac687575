import sys

from tolalloc.cli import main

sys.exit(main())
