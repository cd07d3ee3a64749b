"""`python -m matte_mitsuba` prints the search path to pass to `mitsuba -a`: the plugin folder
of the running Mitsuba release, then the package folder (so a scene may name a packaged table as
``ground_truth/<name>.json``), separated by ``;`` as ``-a`` takes them."""

from . import PACKAGE_ROOT, PLUGIN_ROOT

print("%s;%s" % (PLUGIN_ROOT, PACKAGE_ROOT))
