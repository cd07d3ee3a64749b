# The two entry points the README documents. Each installs what it needs by itself:
#   make main   the main job
#   make test   every test (the kernels' fast tier, format and lint checks, the other Rust tests,
#               then the Mitsuba plugin's pytest suite); .ci/run calls it
# and two more (not set-up commands; they need the same things as main):
#   make bench  matte against Mitsuba in one run (bench_out/bench.json)
#   make dist   the release files in dist/: the sdist, the manylinux wheels for Linux x86_64
#               and aarch64 (cross-built), each repaired by auditwheel, and the macOS arm64
#               wheel (cross-built with Zig, its links checked)
# and one that recomputes data the repository holds:
#   make ground-truth  the simulated microsurfaces' BRDF tables in python/matte_mitsuba/ground_truth/
.PHONY: main test test-rust test-python bench venv plugin rust-release dist ground-truth

PY     := .venv/bin/python
# The matte-mitsuba wheel (plugins, matte_mitsuba, the matte tool), installed into .venv, and
# the Linux aarch64 one, cross-built (cpp/build_plugin.py, MATTE_PLATFORM=linux-aarch64).
WHEEL  := dist/matte_mitsuba-0.1.0-py3-none-linux_x86_64.whl
WHEEL_AARCH64 := dist/matte_mitsuba-0.1.0-py3-none-linux_aarch64.whl
WHEEL_MACOS := dist/matte_mitsuba-0.1.0-py3-none-macosx_11_0_arm64.whl
# The wheel's inputs: sources, the package with its tables, and the package data setup.py copies
# in (the bundled scenes, the study report's slices); not the copies themselves.
SOURCES := $(shell find rust cpp python/matte_mitsuba mitsuba_scenes -type f -not -path '*/plugins/*' -not -path '*/bin/*' -not -path 'python/matte_mitsuba/lib/*' \
	-not -name '_build.py' -not -path '*__pycache__*' -not -path 'python/matte_mitsuba/scenes/*' \
	-not -path 'python/matte_mitsuba/truth_slices/*') Cargo.toml Cargo.lock build.rs pyproject.toml setup.py MANIFEST.in \
	$(wildcard docs/microgeometry/truth_slice_*.png docs/microgeometry/slices_*_r0.3_rho0.8.png)
# The installed `matte` command (the wheel's, in .venv): the checkout is one more environment
# where matte is installed, and its commands find their Mitsuba side as a user's do.
MATTE  := .venv/bin/matte

main: plugin
	$(MATTE) validate --all -o validate_out

bench: plugin
	$(MATTE) bench -o bench_out

# The fast tier first (the kernels' tests: matte-brdf alone, no venv, no wheel; its thorough
# statistical sweeps, #[ignore]d there, run first in test-rust), then the venv
# and the installed wheel, then two chains side by side (make -j2; each line of output whole):
# the Rust lint and tests, and the release files with the Python and C++ checks and the plugin's
# pytest suite. They share no build folder (target/debug against target/release and the
# cross targets), so neither waits for the other's cargo lock, and each uses the core the other
# leaves idle (qemu, downloads, links). pytest runs in two worker processes, each taking whole
# files (a module's set-up, such as the release matrix's environments, runs once).
test:
	cargo fmt --check
	cargo test --quiet -p matte-brdf
	$(MAKE) --no-print-directory plugin
	$(MAKE) --no-print-directory -j2 --output-sync=line test-rust test-python

# (cargo is kept off make's jobserver, whose two slots the chains hold: it runs its own jobs.
# test-rust ends first, while test-python still builds the release files: it then makes the
# release matrix's environments, which pytest would otherwise make first.)
test-rust:
	env -u MAKEFLAGS -u MFLAGS cargo test --quiet -p matte-brdf -- --ignored
	env -u MAKEFLAGS -u MFLAGS cargo clippy --quiet --workspace --all-targets -- -D warnings
	env -u MAKEFLAGS -u MFLAGS cargo test --quiet --workspace --exclude matte-brdf
	setup/release_venvs.sh --environments

test-python: dist
	.venv/bin/ruff check --quiet .
	.venv/bin/ruff format --check --quiet .
	clang-format --dry-run --Werror cpp/*.h cpp/*.cpp
	$(PY) -m pytest -q -n 2 --dist loadfile tests/plugin tests/harness

# Every table with its fixed seed and photon count (docs/microgeometry.md, "The tabulated
# ground-truth BRDF"; about 22 min on 2 shared cores).
ground-truth:
	cargo build --release --quiet
	validation/generators/ground_truth_tables.sh

# Debian's libllvm19, .venv with the pinned wheels (fast when already done).
venv:
	@setup/setup_venv.sh

# The venv and the Rust half of the wheel (cargo's release build of the kernels and the `matte`
# command, which needs no venv) side by side, then the wheel, whose build finds the Rust built.
plugin:
	@$(MAKE) --no-print-directory -j2 venv rust-release
	@$(MAKE) --no-print-directory $(WHEEL)

# (cpp/build_plugin.py's RUST_BUILD, which the wheel's build then finds done; cargo off make's
# jobserver: it runs its own jobs.)
rust-release:
	@env -u MAKEFLAGS -u MFLAGS cargo build --release --quiet -p matte-plugin -p matte

# The libraries the plugin loads from the mitsuba and drjit wheels it requires: not copied in.
PROVIDED := libmitsuba.so libdrjit-core.so libdrjit-extra.so libnanothread.so

# The sdist (python -m build, the PEP 517 front end; MANIFEST.in says what goes in), both Linux
# wheels repaired by auditwheel to the lowest manylinux tag their symbols allow, and the macOS
# wheel (nothing to repair: it links only the system's and Mitsuba's libraries); twine checks all.
dist: $(WHEEL) $(WHEEL_AARCH64) $(WHEEL_MACOS)
	@rm -f dist/matte_mitsuba-*.tar.gz dist/matte_mitsuba-*manylinux*.whl
	@mkdir -p target
	@$(PY) -m build --sdist --no-isolation --outdir dist . > target/sdist.log 2>&1 || (cat target/sdist.log; false)
	@for w in $(WHEEL) $(WHEEL_AARCH64); do \
		PATH="$(CURDIR)/.venv/bin:$$PATH" auditwheel repair $$w -w dist $(addprefix --exclude ,$(PROVIDED)) \
			> target/auditwheel.log 2>&1 || { cat target/auditwheel.log; exit 1; }; done
	.venv/bin/twine check --strict dist/matte_mitsuba-*.tar.gz dist/matte_mitsuba-*manylinux*.whl $(WHEEL_MACOS)

# `pip wheel .` is the standard build (pyproject.toml, setup.py -> cpp/build_plugin.py); here
# against the venv's own Mitsuba (no build isolation), then installed into the venv.
$(WHEEL): $(SOURCES) setup/requirements.txt | venv
	@rm -f dist/matte_mitsuba-*linux_x86_64.whl
	$(PY) -m pip wheel . --no-deps --no-build-isolation -w dist -q --disable-pip-version-check
	$(PY) -m pip install --force-reinstall --no-deps -q --disable-pip-version-check $(WHEEL)

# The same build for Linux aarch64, with the cross toolchain setup_venv.sh installs. The three
# wheels are built one after the other (order-only prerequisites), also under make -j: each
# `pip wheel .` of a checkout writes the same build/ and egg-info folders.
$(WHEEL_AARCH64): $(SOURCES) setup/requirements.txt | venv $(WHEEL)
	@rm -f dist/matte_mitsuba-*linux_aarch64.whl
	MATTE_PLATFORM=linux-aarch64 $(PY) -m pip wheel . --no-deps --no-build-isolation -w dist -q --disable-pip-version-check

# The same build for macOS arm64, cross-built with Zig (ziglang and cargo-zigbuild from the
# venv): every layer linked with undefined symbols an error.
$(WHEEL_MACOS): $(SOURCES) setup/requirements.txt | venv $(WHEEL_AARCH64)
	@rm -f dist/matte_mitsuba-*macosx*.whl
	MATTE_PLATFORM=macos-arm64 PATH="$(CURDIR)/.venv/bin:$$PATH" $(PY) -m pip wheel . --no-deps --no-build-isolation -w dist -q --disable-pip-version-check
