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
	@echo "== 1/7 draft: the project's A-line skirt as AAMA DXF, and with its seams and arrangements as XVC"
	@$(VGD) draft skirt -o $(DEMO_OUT)/a-line-skirt.dxf
	@$(VGD) draft skirt -o $(DEMO_OUT)/a-line-skirt.xvc
	@echo "== 2/7 import: AAMA DXF -> XVC document, validated against schemas/xvc.xsd and the reference rules"
	@$(VGD) import data/garments/a-line-skirt.dxf --report -o $(DEMO_OUT)/skirt.xvc
	@$(VGD) validate $(DEMO_OUT)/a-line-skirt.xvc
	@echo "== 3/7 draw the patterns (schemas/xvc-to-svg.xsl)"
	@$(VGD) svg $(DEMO_OUT)/a-line-skirt.xvc -o $(DEMO_OUT)/skirt.svg
	@echo "== 4/7 its seams, as vgd suggests them from names, lengths and notches"
	@$(VGD) seams suggest $(DEMO_OUT)/a-line-skirt.xvc --size 38
	@echo "== 5/7 the default mannequin (size 38, EN 13402-3) as OBJ"
	@$(VGD) mannequin --size 38 -o $(DEMO_OUT)/mannequin-38.obj
	@echo "== 6/7 sew and drape the skirt on it (certificate: penetration, seams, strain, contact, energy)"
	@$(VGD) drape $(DEMO_OUT)/a-line-skirt.xvc --size 38 -o $(DEMO_OUT)/drape-skirt || test $$? -eq 3
	@echo "== 6b/7 headless previews of the draped skirt (OpenGL off-screen, docs/render.md)"
	@$(VGD) render $(DEMO_OUT)/drape-skirt --views front,back,left,right,three-quarter --size 1024x1024 -o $(DEMO_OUT)/previews
	@echo "== 7/7 simulate the seed's flag in the wind for 2 s (data/scenes/flag.json)"
	@$(VGD) simulate data/scenes/flag.json --duration 2 -o $(DEMO_OUT)/flag
	@echo "outputs in $(DEMO_OUT)/: a-line-skirt.dxf a-line-skirt.xvc skirt.svg mannequin-38.obj"
	@echo "  drape-skirt/ (garment.obj avatar.obj certificate.json) flag/ (OBJ frames)"
	@echo "  previews/ (front.png back.png left.png right.png three-quarter.png: the draped skirt, 1024 x 1024)"

asan:
	@$(MAKE) test BUILD=build-asan BUILD_TYPE=RelWithDebInfo CMAKE_ARGS="-DVGD_SANITIZE=ON -DVGD_BUILD_BENCHMARKS=OFF"

fuzz: deps
	@CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVGD_FUZZ=ON -DVGD_BUILD_BENCHMARKS=OFF > /dev/null
	@cmake --build build-fuzz -j $(JOBS) --target vgd_fuzz_dxf_import vgd_fuzz_scene_files

bench: build
	@$(BUILD)/tests/bench/vgd_bench

clean:
	rm -rf $(BUILD) build-asan build-fuzz out
