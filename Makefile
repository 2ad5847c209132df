# Thin wrapper over the CMake presets. The two commands a user needs:
#   make demo   build adb-demo and run the pile under a budget against exact contacts and GImpact
#               (installs missing system packages first)
#   make test   build and run the test suite
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: all deps build demo test test-asan test-tsan fuzz bench python clean

all: build

# Installs the Debian packages only when one is missing (the script checks each).
deps:
	@bash cmake/install-deps.sh

build: deps
	cmake --preset release
	cmake --build --preset release -j $(JOBS)

# The main job: the gallery's pile under a per-step budget, the same with exact contacts and
# with GImpact, for 10 s (600 steps: every run's pile has settled and fallen asleep, GImpact's
# from step 328, exact contacts' from 336; the scene's own 6 s ended 24 steps after that);
# prints the comparison and the path of a picture (build/demo/comparison.png).
# Builds adb-demo alone: a fresh machine need not wait for the tests.
demo: deps
	cmake --preset release
	cmake --build --preset release -j $(JOBS) --target adb-demo
	./build/bin/adb-demo --scene demos/scenes/pile.json --steps 600 --compare --render --probe-every 60 --out build/demo

test: build
	ctest --preset release -j $(JOBS)

# The same suite under AddressSanitizer + UndefinedBehaviorSanitizer.
test-asan: deps
	cmake --preset asan-ubsan
	cmake --build --preset asan-ubsan -j $(JOBS)
	ctest --preset asan-ubsan -j $(JOBS)

# The Bullet and scene tests under ThreadSanitizer, every world's pair queries on 2 threads
# (ADB_TEST_THREADS); not part of make test, for CI's time.
test-tsan: deps
	cmake --preset tsan
	cmake --build --preset tsan -j $(JOBS) --target adb_bullet_tests adb_scene_tests
	ctest --preset tsan -j $(JOBS)

# libFuzzer on every fuzz target for FUZZ_SECONDS each (tests/fuzz/run_fuzz.sh; clang).
FUZZ_SECONDS ?= 60
fuzz:
	@bash cmake/install-deps.sh fuzz
	cmake --preset fuzz
	cmake --build --preset fuzz -j $(JOBS)
	bash tests/fuzz/run_fuzz.sh $(FUZZ_SECONDS)

# The Python module installed into a venv (.venv) that sees Debian's numpy and matplotlib;
# then `. .venv/bin/activate && python3 -c "import adb"` (docs/python.md).
python: deps
	/usr/bin/python3 -m venv --system-site-packages .venv
	.venv/bin/pip install --no-build-isolation ./python

bench: build
	./build/bin/adb-bench-core

clean:
	rm -rf build build-debug build-asan build-tsan build-fuzz python/build python/*.egg-info
