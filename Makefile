# iacsg -- interval-arithmetic ray tracer for CSG of implicit surfaces.
#
#   make            build build/iacsg (and build/libiacsg.a)
#   make test       install missing Debian packages, build, run every test (ends "N passed, N failed")
#   make demo       render the README's first example
#   make gallery    render examples/*.csg into the contact sheet docs/gallery.png
#   make deps       install the Debian packages the project needs (apt-get; sudo when not root)
#   make bench-ia   nanoseconds per interval operation, host and device, rigorous and fast
#   make bench      render the benchmark suite of issue 5 and write BENCHMARKS.md (BENCH_QUICK=1: a quick look)
#   make fuzz       libFuzzer on the expression compiler for FUZZ_SECONDS (default 60)
#
# BUILD=dir SAN=1 builds everything under AddressSanitizer and UndefinedBehaviorSanitizer in another directory.

BUILD ?= build
CC ?= gcc
CXX ?= g++
SAN ?=

WARN = -Wall -Wextra -pedantic -Werror
OPT = -O2 -g
ifeq ($(SAN),1)
OPT = -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
endif
CFLAGS_ALL = -std=c11 $(WARN) $(OPT) -I. -Isrc -I$(BUILD) -D_POSIX_C_SOURCE=200809L $(CFLAGS)
CXXFLAGS_ALL = -std=c++17 -Wall -Wextra -Werror $(OPT) -I. -Isrc $(CXXFLAGS)
IMAGE_LIBS = -lOpenImageIO -lOpenImageIO_Util
LIBS = -lOpenCL $(IMAGE_LIBS) -lmpfr -lgmp -lm -lstdc++
CLI_LIBS = -lOpenCL -lm -ldl
LDFLAGS_ALL = $(OPT) $(LDFLAGS)

DEB_PACKAGES = gcc g++ make valgrind clang libclang-rt-14-dev pocl-opencl-icd ocl-icd-opencl-dev opencl-headers libopenimageio-dev libmpfr-dev

# OpenCL sources, in dependency order: they are concatenated (local #include lines dropped) into the binary.
IA_CL_HEADERS = ia/compat.h ia/round.h ia/interval.h ia/arith.h ia/elem.h ia/vec.h
KERNEL_SOURCES ?= kernels/compat.h kernels/params.h kernels/camera.h kernels/traverse.h \
                  kernels/packet.h kernels/tile_rays.h kernels/tile.h kernels/light.h kernels/shade.h kernels/render.cl
# The segment path's program (src/render_scene.c): the same ia/ headers, the scene's solids, then these.
SCENE_KERNEL_SOURCES = kernels/compat.h kernels/params.h kernels/camera.h kernels/traverse.h kernels/csg_node.h \
                       kernels/scene_data.h kernels/bvh.h kernels/segments.h kernels/classify.h kernels/weave.h \
                       kernels/tile_rays.h kernels/surface.h kernels/scene_trace.h kernels/light.h kernels/render_scene.cl
TEST_CL_SOURCES = $(sort $(wildcard tests/*.cl))

LIB_C = $(filter-out src/cli%.c,$(wildcard ia/*.c implicits/*.c src/*.c))
LIB_CXX = $(wildcard src/*.cpp)
CLI_C = $(wildcard src/cli*.c)
TEST_C = $(filter-out %_fp.c,$(wildcard tests/*.c))
TEST_FP_C = $(wildcard tests/*_fp.c)

LIB_OBJ = $(LIB_C:%.c=$(BUILD)/%.o) $(LIB_CXX:%.cpp=$(BUILD)/%.o) $(BUILD)/embedded_ia.o \
          $(if $(KERNEL_SOURCES),$(BUILD)/embedded_kernels.o) $(BUILD)/embedded_scene_kernels.o
CLI_OBJ = $(CLI_C:%.c=$(BUILD)/%.o)
TEST_OBJ = $(TEST_C:%.c=$(BUILD)/%.o) $(TEST_FP_C:%.c=$(BUILD)/%.f32.o) $(TEST_FP_C:%.c=$(BUILD)/%.f64.o) \
           $(if $(TEST_CL_SOURCES),$(BUILD)/embedded_tests.o)

.PHONY: all deps test check demo bench-ia fuzz clean bench
all: $(BUILD)/iacsg

deps:
	@missing=$$(for p in $(DEB_PACKAGES); do \
	    dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	    echo "make deps: installing" $$missing; \
	    if [ "$$(id -u)" = 0 ]; then sudo=; else sudo=sudo; fi; \
	    $$sudo apt-get update -q && DEBIAN_FRONTEND=noninteractive $$sudo apt-get install -y -q $$missing; \
	fi

$(BUILD)/libiacsg.a: $(LIB_OBJ)
	ar rcs $@ $^

# The command is not linked with OpenImageIO: it loads libiacsg_image.so, beside it, in a child process
# (src/cli_writer.c), so that the ~180 ms of linking OpenImageIO's libraries overlap OpenCL's start.
$(BUILD)/iacsg: $(CLI_OBJ) $(BUILD)/libiacsg.a $(BUILD)/libiacsg_image.so
	$(CC) $(LDFLAGS_ALL) -o $@ $(CLI_OBJ) $(BUILD)/libiacsg.a $(CLI_LIBS)

$(BUILD)/libiacsg_image.so: $(BUILD)/pic/src/image_oiio.o $(BUILD)/pic/src/error.o
	$(CXX) $(LDFLAGS_ALL) -shared -o $@ $^ $(IMAGE_LIBS)

$(BUILD)/iacsg-tests: $(TEST_OBJ) $(BUILD)/libiacsg.a
	$(CC) $(LDFLAGS_ALL) -o $@ $(TEST_OBJ) $(BUILD)/libiacsg.a $(LIBS)

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -MMD -MP -c $< -o $@
$(BUILD)/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS_ALL) -MMD -MP -c $< -o $@
$(BUILD)/pic/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -fPIC -MMD -MP -c $< -o $@
$(BUILD)/pic/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS_ALL) -fPIC -MMD -MP -c $< -o $@
$(BUILD)/%.o: $(BUILD)/%.c
	$(CC) $(CFLAGS_ALL) -c $< -o $@

# tests/*_fp.c are compiled twice, for float and for double intervals; TEST_FP(name) becomes name_f32/_f64.
$(BUILD)/tests/%.f32.o: tests/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -MMD -MP -c $< -o $@
$(BUILD)/tests/%.f64.o: tests/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -DIA_FP64 -MMD -MP -c $< -o $@

$(BUILD)/tests/main.o: $(BUILD)/tests.inc
$(BUILD)/tests/main.o: CFLAGS += -DIACSG_SOURCE_DIR_DEFAULT='"$(CURDIR)"' -DIACSG_BINARY_DEFAULT='"$(CURDIR)/$(BUILD)/iacsg"'
$(BUILD)/tests.inc: $(TEST_C) $(TEST_FP_C)
	@mkdir -p $(dir $@)
	sed -n 's/^TEST(\([a-zA-Z0-9_]*\)).*/X(\1)/p' $(TEST_C) > $@.tmp
	sed -n 's/^TEST_FP(\([a-zA-Z0-9_]*\)).*/X(\1_f32)\nX(\1_f64)/p' $(TEST_FP_C) >> $@.tmp
	mv $@.tmp $@

$(BUILD)/embed: src/tools/embed.c
	@mkdir -p $(dir $@)
	$(CC) -std=c11 $(WARN) -O1 -o $@ $<
$(BUILD)/embedded_ia.c: $(IA_CL_HEADERS) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_ia $(IA_CL_HEADERS) > $@
$(BUILD)/embedded_kernels.c: $(KERNEL_SOURCES) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_kernels $(KERNEL_SOURCES) > $@
$(BUILD)/embedded_scene_kernels.c: $(SCENE_KERNEL_SOURCES) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_scene_kernels $(SCENE_KERNEL_SOURCES) > $@
$(BUILD)/embedded_tests.c: $(TEST_CL_SOURCES) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_tests $(TEST_CL_SOURCES) > $@

# The user-facing targets install what is missing first, then build in a fresh make (so the new headers count).
# `make test` runs the suite, the suite under ASan+UBSan (build-asan/), and valgrind on the compiler
# (tests/run.sh); `make check` is the quick loop: the plain suite only.
test: deps
	@$(MAKE) --no-print-directory $(BUILD)/iacsg-tests $(BUILD)/iacsg
	@$(MAKE) --no-print-directory BUILD=build-asan SAN=1 build-asan/iacsg-tests build-asan/iacsg
	@BUILD=$(BUILD) ASAN_BUILD=build-asan tests/run.sh

check: $(BUILD)/iacsg-tests $(BUILD)/iacsg
	$(BUILD)/iacsg-tests

demo: deps
	@$(MAKE) --no-print-directory $(BUILD)/iacsg
	$(BUILD)/iacsg "min(sphere,torus)" -eps 1e-5

# The examples' scenes as one contact sheet, through the embedding example: the single expressions of Fig. 2, 3, 7
# and 8 of the Hijazi seed, then the scenes of regions and surfaces (the segment path; Fig. 5 among them).
SEGMENT_SCENES = examples/fig2_cube_sphere_regions.csg examples/machined_part.csg examples/icos.csg examples/sesc.csg
GALLERY_SCENES = $(sort $(filter-out $(SEGMENT_SCENES),$(wildcard examples/*.csg))) $(SEGMENT_SCENES)
$(BUILD)/examples/embed: examples/embed.c $(BUILD)/libiacsg.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -o $@ $< $(BUILD)/libiacsg.a $(LIBS)
gallery: deps
	@$(MAKE) --no-print-directory $(BUILD)/examples/embed
	$(BUILD)/examples/embed docs/gallery.png 256 3 $(GALLERY_SCENES)

bench-ia: deps
	@$(MAKE) --no-print-directory $(BUILD)/iacsg-tests
	$(BUILD)/iacsg-tests bench_ia

# Not part of `make test`: about 15 minutes (tests/bench/bench.sh says what it measures and how).
bench: deps
	@$(MAKE) --no-print-directory $(BUILD)/iacsg
	BENCH_QUICK=$(BENCH_QUICK) BENCH_BUILD=$(BUILD)/bench sh tests/bench/bench.sh $(BUILD)/iacsg

# libFuzzer over the lexer, parser and compiler, seeded from examples/ and tests/data/fuzz/. New crashes land in
# build-fuzz/crash-*: copy each into tests/data/fuzz/ so that every `make test` replays it.
FUZZ_SECONDS ?= 60
FUZZ_SRC = tests/fuzz/fuzz_expr.c tests/expr_exercise.c $(wildcard implicits/*.c) ia/decimal.c src/error.c src/clrt.c
build-fuzz/fuzz_expr: $(FUZZ_SRC) $(BUILD)/embedded_ia.c
	@mkdir -p $(dir $@)
	clang -std=c11 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -I. -Isrc \
	    -D_POSIX_C_SOURCE=200809L $^ -lOpenCL -lm -o $@

fuzz: deps
	@$(MAKE) --no-print-directory build-fuzz/fuzz_expr
	@mkdir -p build-fuzz/corpus
	build-fuzz/fuzz_expr -max_total_time=$(FUZZ_SECONDS) -timeout=20 -rss_limit_mb=4096 -max_len=8192 \
	    -print_final_stats=1 -artifact_prefix=build-fuzz/ build-fuzz/corpus examples tests/data/fuzz

clean:
	rm -rf build build-asan build-fuzz

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
