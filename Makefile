# The two commands of the README, and a few more for developers.
#
#   make demo   a Lift rollout that prints what happened
#   make test   every test (Rust and Python)
#
# Both need only a Rust toolchain, python3 with pip, pkg-config and libEGL with Mesa's
# software renderer (installed with apt-get when missing and possible). MuJoCo 3.17.0 is fetched by the build itself
# (build-support/README.md).

CARGO ?= cargo
PYTHON ?= python3

.PHONY: demo test test-rust test-python bench fmt lint doc prerequisites clean

demo: prerequisites
	$(CARGO) run --release -p examples --example lift_demo

test: test-rust test-python

test-rust: prerequisites
	$(CARGO) test --workspace --all-targets --features gym-core/proptest-support,robosuite-env/render
	$(CARGO) test --workspace --doc --features robosuite-env/render

test-python: prerequisites
	bash python/scripts/test.sh

bench: prerequisites
	$(CARGO) run --release -p examples --example benchmark -- --json bench.json

fmt:
	$(CARGO) fmt --all

lint: prerequisites
	$(CARGO) fmt --all -- --check
	$(CARGO) clippy --workspace --all-targets -- -D warnings

doc: prerequisites
	$(CARGO) doc --workspace --no-deps

prerequisites:
	@command -v $(CARGO) >/dev/null || { echo "make: cargo not found; install Rust from https://rustup.rs"; exit 1; }
	@command -v $(PYTHON) >/dev/null || { echo "make: $(PYTHON) not found; install Python 3 with pip"; exit 1; }
	@$(PYTHON) -m pip --version >/dev/null 2>&1 || { echo "make: pip is missing; install it (python3 -m ensurepip)"; exit 1; }
	@command -v pkg-config >/dev/null || sh build-support/install-pkg-config.sh
	@sh build-support/install-render-libs.sh

clean:
	$(CARGO) clean
