#!/usr/bin/python3
"""lk_fleet's command: `/usr/bin/python3 scripts/lk_fleet.py gap|sweep ...` (usage and exit status: --help,
docs/fleet.md). The code is the package beside this file, scripts/lk_fleet/ (its __init__.py lists the
modules); `python3 -m lk_fleet` from scripts/ runs the same command.

This file and the package share a name on purpose, the command keeping its name. It is never imported:
run as a script its folder comes first on the path, and there `import lk_fleet` finds the package (a
package's folder takes precedence over a module of the same name in one folder).
"""
import sys

from lk_fleet.cli import main

# Guarded: a LocalCluster's worker processes are spawned, and run the parent's main script again.
if __name__ == "__main__":
    sys.exit(main())
