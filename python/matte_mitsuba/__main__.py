"""`python -m matte_mitsuba` prints the folder to pass to `mitsuba -a`."""

from . import PLUGIN_ROOT

print(PLUGIN_ROOT)
