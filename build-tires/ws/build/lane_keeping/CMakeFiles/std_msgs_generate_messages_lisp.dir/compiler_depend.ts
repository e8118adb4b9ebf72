# CMAKE generated file: DO NOT EDIT!
# Timestamp file for custom commands dependencies management for std_msgs_generate_messages_lisp.
