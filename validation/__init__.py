"""What checks matte against Mitsuba and against references, run from a checkout (the installed
package holds what the `matte` tool runs; see python/matte_mitsuba/):

* ``verify_semantics.py``: the renderer-semantics claims of docs/renderer-semantics.md, each
  checked against live Mitsuba;
* ``mitsuba_testsuite.py`` (and ``.md``): Mitsuba's own surface test scenes against matte;
* ``check_harvest.py``: Mitsuba's verdict on the harvested property list;
* ``sampling_scenes.py``: the samplers' efficiency in scenes, both renderers.

Beside them: ``generators/`` (scripts that write files the repository holds: fits, harvested
tables, ground-truth tables, the docs' pictures) and ``experiments/`` (one-off studies behind
numbers in docs/, with their results). The tests' recorded references are written by the
``generate_reference.py`` beside each test; the development environment is ``setup/`` at the
top of the repository.
"""
