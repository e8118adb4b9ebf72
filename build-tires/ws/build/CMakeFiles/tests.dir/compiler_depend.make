# Empty custom commands generated dependencies file for tests.
# This may be replaced when dependencies are built.
