# Empty custom commands generated dependencies file for std_msgs_generate_messages_cpp.
# This may be replaced when dependencies are built.
