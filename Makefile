# Thin wrapper around CMake. `make demo` and `make test` work on a fresh Debian 12
# machine as root: they install what is missing (.ci/install-deps), configure,
# build with ccache on all cores, then run the demo or the whole test suite.
BUILD      ?= build
BUILD_TYPE ?= Release
JOBS       ?= $(shell nproc)
CMAKE_ARGS ?=
VGD        := $(BUILD)/apps/vgd/vgd
STUDIO     := $(BUILD)/apps/vgd-studio/vgd-studio
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
	@echo "== 1/10 draft: the project's A-line skirt and T-shirt (AAMA DXF, and XVC with their seams and arrangements)"
	@$(VGD) draft skirt -o $(DEMO_OUT)/a-line-skirt.dxf
	@$(VGD) draft skirt -o $(DEMO_OUT)/a-line-skirt.xvc
	@$(VGD) draft tshirt -o $(DEMO_OUT)/t-shirt.xvc
	@echo "== 2/10 import: AAMA DXF -> XVC document, validated against schemas/xvc.xsd and the reference rules"
	@$(VGD) import data/garments/a-line-skirt.dxf --report -o $(DEMO_OUT)/skirt.xvc
	@$(VGD) validate $(DEMO_OUT)/a-line-skirt.xvc
	@echo "== 3/10 draw the patterns (schemas/xvc-to-svg.xsl)"
	@$(VGD) svg $(DEMO_OUT)/a-line-skirt.xvc -o $(DEMO_OUT)/skirt.svg
	@echo "== 4/10 their seams, as vgd suggests them from names, lengths and notches"
	@$(VGD) seams suggest $(DEMO_OUT)/a-line-skirt.xvc --size 38
	@echo "== 5/10 the default mannequin (size 38, EN 13402-3) as OBJ"
	@$(VGD) mannequin --size 38 -o $(DEMO_OUT)/mannequin-38.obj
	@echo "== 6/10 sew and drape the skirt and the T-shirt on it (certificates: penetration, seams, strain, contact, energy)"
	@$(VGD) drape $(DEMO_OUT)/a-line-skirt.xvc --size 38 -o $(DEMO_OUT)/drape-skirt --trj $(DEMO_OUT)/drape-skirt/skirt.trj || test $$? -eq 3
	@$(VGD) drape $(DEMO_OUT)/t-shirt.xvc --size 38 -o $(DEMO_OUT)/drape-tshirt || test $$? -eq 3
	@echo "== 7/10 headless previews (OpenGL off-screen, docs/render.md)"
	@$(VGD) render $(DEMO_OUT)/drape-skirt --views front,back,left,right,three-quarter --size 1024x1024 -o $(DEMO_OUT)/previews
	@$(VGD) render $(DEMO_OUT)/drape-tshirt --views front,three-quarter --size 1024x1024 -o $(DEMO_OUT)/previews-tshirt
	@echo "== 8/10 publish: the skirt's trajectory compressed (1 mm), VRML (static, animated), glTF and a web catalogue"
	@$(VGD) compress $(DEMO_OUT)/drape-skirt/skirt.trj -o $(DEMO_OUT)/drape-skirt/skirt.wvt --max-error-mm 1
	@$(VGD) export $(DEMO_OUT)/drape-skirt/skirt.trj --vrml animated --decimate 4 -o $(DEMO_OUT)/skirt-animated.wrl --avatar $(DEMO_OUT)/drape-skirt/avatar.obj
	@$(VGD) export $(DEMO_OUT)/drape-skirt/skirt.trj -o $(DEMO_OUT)/skirt.wrl --gltf $(DEMO_OUT)/skirt.glb --avatar $(DEMO_OUT)/drape-skirt/avatar.obj
	@$(VGD) export $(DEMO_OUT)/drape-skirt $(DEMO_OUT)/drape-tshirt --web $(DEMO_OUT)/web --live-flag --title "vgd demo" || echo "(web catalogue skipped: X_ITE not installed)"
	@echo "== 9/10 simulate the seed's flag in the wind for 2 s (data/scenes/flag.json)"
	@$(VGD) simulate data/scenes/flag.json --duration 2 -o $(DEMO_OUT)/flag
	@echo "== 10/10 the studio, off-screen: the skirt draped from its Drape button at the preview preset (data/studio/demo.txt)"
	@$(STUDIO) --headless $(DEMO_OUT)/a-line-skirt.xvc --script data/studio/demo.txt --screenshot $(DEMO_OUT)/studio.png
	@echo "outputs in $(DEMO_OUT)/: a-line-skirt.dxf a-line-skirt.xvc t-shirt.xvc skirt.svg mannequin-38.obj"
	@echo "  drape-skirt/ drape-tshirt/ (garment.obj avatar.obj certificate.json contact-pressure.json; skirt.trj skirt.wvt) flag/ (OBJ frames)"
	@echo "  previews/ previews-tshirt/ (PNG, 1024 x 1024), skirt.wrl skirt-animated.wrl skirt.glb, web/index.html, studio.png"

asan:
	@$(MAKE) test BUILD=build-asan BUILD_TYPE=RelWithDebInfo CMAKE_ARGS="-DVGD_SANITIZE=ON -DVGD_BUILD_BENCHMARKS=OFF"

fuzz: deps
	@CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVGD_FUZZ=ON -DVGD_BUILD_BENCHMARKS=OFF > /dev/null
	@cmake --build build-fuzz -j $(JOBS) --target vgd_fuzz_dxf_import vgd_fuzz_scene_files vgd_fuzz_trj_files vgd_fuzz_avatar_files vgd_fuzz_piece_names \
		vgd_fuzz_xvc_files vgd_fuzz_png_files vgd_fuzz_lab_csv vgd_fuzz_mannequin_cache

bench: build
	@$(BUILD)/tests/bench/vgd_bench

clean:
	rm -rf $(BUILD) build-asan build-fuzz out
