# The two entry points the README documents. Each installs what it needs by itself.
#   make main   the main job
#   make test   every test
.PHONY: main test

main:
	cargo run --release --quiet -- tables

test:
	cargo test --quiet
