# Thin wrapper over the CMake presets. The two commands a user needs:
#   make demo   build and run the pile-scene demo (installs missing system packages first)
#   make test   build and run the test suite
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: all deps build demo test test-asan bench clean

all: build

# Installs the Debian packages only when one is missing (the script checks each).
deps:
	@bash cmake/install-deps.sh

build: deps
	cmake --preset release
	cmake --build --preset release -j $(JOBS)

# The main job: the pile scene with adb's shapes (see build/bin/adb-demo --help).
demo: build
	./build/bin/adb-demo --out build/demo

test: build
	ctest --preset release -j $(JOBS)

# The same suite under AddressSanitizer + UndefinedBehaviorSanitizer.
test-asan: deps
	cmake --preset asan-ubsan
	cmake --build --preset asan-ubsan -j $(JOBS)
	ctest --preset asan-ubsan -j $(JOBS)

bench: build
	./build/bin/adb-bench-core

clean:
	rm -rf build build-debug build-asan
