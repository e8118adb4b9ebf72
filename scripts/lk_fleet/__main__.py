"""`python3 -m lk_fleet gap|sweep ...` (from scripts/, or with scripts/ on the path): the same command as
scripts/lk_fleet.py.

Depends on cli."""
import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
