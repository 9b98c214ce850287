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

# The main job on bundled data: the project's own drafted skirt, imported,
# validated, drawn and meshed. Each step is a plain vgd command.
demo: build
	@mkdir -p $(DEMO_OUT)
	@echo "== 1/6 draft: the project's A-line skirt from the size table (data/garments/a-line-skirt.dxf is the committed copy)"
	@$(VGD) draft skirt -o $(DEMO_OUT)/a-line-skirt.dxf
	@echo "== 2/6 import: AAMA DXF -> XVC document"
	@$(VGD) import data/garments/a-line-skirt.dxf --report -o $(DEMO_OUT)/skirt.xvc
	@echo "== 3/6 validate against schemas/xvc.xsd and the reference rules"
	@$(VGD) validate $(DEMO_OUT)/skirt.xvc
	@echo "== 4/6 draw the patterns (schemas/xvc-to-svg.xsl)"
	@$(VGD) svg $(DEMO_OUT)/skirt.xvc -o $(DEMO_OUT)/skirt.svg
	@echo "== 5/6 mesh the sample size (CGAL, 1 cm spacing, 25 deg) and write Triangle files"
	@$(VGD) mesh $(DEMO_OUT)/skirt.xvc --triangle-files $(DEMO_OUT)/mesh
	@echo "== 6/6 simulate the seed's flag in the wind for 2 s (data/scenes/flag.json)"
	@$(VGD) simulate data/scenes/flag.json --duration 2 -o $(DEMO_OUT)/flag --profile
	@echo "outputs in $(DEMO_OUT)/: a-line-skirt.dxf skirt.xvc skirt.svg mesh/ flag/ (OBJ frames)"

asan:
	@$(MAKE) test BUILD=build-asan BUILD_TYPE=RelWithDebInfo CMAKE_ARGS="-DVGD_SANITIZE=ON -DVGD_BUILD_BENCHMARKS=OFF"

fuzz: deps
	@CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVGD_FUZZ=ON -DVGD_BUILD_BENCHMARKS=OFF > /dev/null
	@cmake --build build-fuzz -j $(JOBS) --target vgd_fuzz_dxf_import

bench: build
	@$(BUILD)/tests/bench/vgd_bench

clean:
	rm -rf $(BUILD) build-asan build-fuzz out
