# Empty custom commands generated dependencies file for download_extra_data.
# This may be replaced when dependencies are built.
