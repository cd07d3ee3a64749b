"""What checks matte against Mitsuba and against references, run from a checkout (the installed
package holds what the `matte` tool runs; see python/matte_mitsuba/):

* ``verify_semantics.py``: the renderer-semantics claims of docs/renderer-semantics.md, each
  checked against live Mitsuba;
* ``mitsuba_testsuite.py`` (and ``.md``): Mitsuba's own surface test scenes against matte;
* ``check_harvest.py``: Mitsuba's verdict on the harvested property list;
* ``mitsuba_sampler_reference.py``: the samplers' reference values of tests/render/samplers.rs;
* ``sampling_scenes.py``: the samplers' efficiency in scenes, both renderers.

Beside them: ``setup/`` (the development environment: ``setup_venv.sh``,
``requirements.txt``, ``check_env.py``), ``generators/`` (scripts that write files the
repository holds: fits, harvested tables, ground-truth tables, the docs' pictures) and
``experiments/`` (one-off studies behind numbers in docs/).
"""
