# Thin wrapper around CMake. `make demo` and `make test` work on a fresh Debian 12
# machine as root: they install what is missing (.ci/install-deps), configure,
# build with ccache on all cores, then run the demo or the whole test suite.
BUILD      ?= build
BUILD_TYPE ?= Release
JOBS       ?= $(shell nproc)
CMAKE_ARGS ?=
VGD        := $(BUILD)/apps/vgd/vgd
DEMO_OUT   ?= out/demo

.PHONY: all deps configure build test demo asan fuzz bench clean help

all: build

help:
	@echo "make demo    install deps, build, run the main job on bundled data"
	@echo "make test    install deps, build, run every test (ctest)"
	@echo "make asan    the test suite under AddressSanitizer + UBSan (build-asan/)"
	@echo "make fuzz    build the libFuzzer targets with clang (build-fuzz/)"
	@echo "make bench   build and run the benchmarks"

deps:
	@.ci/install-deps

configure: deps
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_ARGS) > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
	@$(BUILD)/apps/vgd/vgd demo -o $(DEMO_OUT)

asan:
	@$(MAKE) test BUILD=build-asan BUILD_TYPE=RelWithDebInfo CMAKE_ARGS="-DVGD_SANITIZE=ON -DVGD_BUILD_BENCHMARKS=OFF"

fuzz: deps
	@CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVGD_FUZZ=ON -DVGD_BUILD_BENCHMARKS=OFF > /dev/null
	@cmake --build build-fuzz -j $(JOBS) --target vgd_fuzz_dxf_import

bench: build
	@$(BUILD)/tests/bench/vgd_bench

clean:
	rm -rf $(BUILD) build-asan build-fuzz out
