# The two commands of the README, and a few more for developers.
#
#   make demo   a Lift rollout that prints what happened
#   make test   every test (Rust and Python)
#   make fuzz   the fuzz suite, longer
#
# Both need only a Rust toolchain, python3 with pip, pkg-config and libEGL with Mesa's
# software renderer (installed with apt-get when missing and possible). MuJoCo 3.17.0 is fetched by the build itself
# (build-support/README.md).

CARGO ?= cargo
PYTHON ?= python3

.PHONY: demo test test-rust test-python fuzz bench fmt lint doc prerequisites clean

demo: prerequisites
	$(CARGO) run --release -p examples --example lift_demo

test: test-rust test-python

test-rust: prerequisites
	$(CARGO) test --workspace --all-targets --features gym-core/proptest-support,robosuite-env/render
	$(CARGO) test --workspace --doc --features robosuite-env/render

test-python: prerequisites
	bash python/scripts/test.sh

# The fuzz suite at length (README, "Fuzzing"): 256 proptest cases per Rust property and 300
# Hypothesis examples per Python property; `make test` runs the same suite briefly.
fuzz: prerequisites
	FUZZ_CASES=256 $(CARGO) test --release -p robosuite-env --test fuzz
	FUZZ_EXAMPLES=300 bash python/scripts/test.sh -k fuzz

bench: prerequisites
	$(CARGO) run --release -p examples --example benchmark -- --json bench.json

fmt:
	$(CARGO) fmt --all

lint: prerequisites
	$(CARGO) fmt --all -- --check
	$(CARGO) clippy --workspace --all-targets -- -D warnings

doc: prerequisites
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc --workspace --no-deps

prerequisites:
	@command -v $(CARGO) >/dev/null || { echo "make: cargo not found; install Rust from https://rustup.rs"; exit 1; }
	@command -v $(PYTHON) >/dev/null || { echo "make: $(PYTHON) not found; install Python 3 with pip"; exit 1; }
	@$(PYTHON) -m pip --version >/dev/null 2>&1 || { echo "make: pip is missing; install it (python3 -m ensurepip)"; exit 1; }
	@command -v pkg-config >/dev/null || sh build-support/install-pkg-config.sh
	@sh build-support/install-render-libs.sh

clean:
	$(CARGO) clean
