# Empty custom commands generated dependencies file for roscpp_generate_messages_py.
# This may be replaced when dependencies are built.
