# generated from catkin/cmake/template/order_packages.context.py.in
source_root_dir = '/work/main/build-tires/ws/src'
whitelisted_packages = ''.split(';') if '' != '' else []
blacklisted_packages = ''.split(';') if '' != '' else []
underlay_workspaces = ''.split(';') if '' != '' else []
