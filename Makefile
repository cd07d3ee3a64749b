# The two entry points the README documents. Each installs what it needs by itself:
#   make main   the main job
#   make test   every test (Rust, then the Mitsuba plugin's pytest suite); .ci/run calls it
# and one more for the speed record (not a set-up command; it needs the same things as main):
#   make bench  matte against Mitsuba in one run (bench_out/bench.json)
.PHONY: main test bench venv plugin

PY     := .venv/bin/python
PLUGIN := validation/matte_mitsuba/plugins/matte_bsdfs.so
SOURCES := $(shell find rust cpp -type f) Cargo.toml Cargo.lock build.rs

main: plugin
	./target/release/matte validate --all -o validate_out

bench: plugin
	./target/release/matte bench -o bench_out

test: plugin
	cargo test --quiet
	$(PY) -m pytest -q tests/plugin tests/renderer

# Debian's libllvm19, .venv with the pinned wheels (fast when already done).
venv:
	@validation/setup_venv.sh

plugin: venv $(PLUGIN)

$(PLUGIN): $(SOURCES) validation/requirements.txt
	@cpp/build_plugin.sh
