# Empty custom commands generated dependencies file for std_msgs_generate_messages_py.
# This may be replaced when dependencies are built.
