# iacsg -- interval-arithmetic ray tracer for CSG of implicit surfaces.
#
#   make            build build/iacsg (and build/libiacsg.a)
#   make test       install missing Debian packages, build, run every test (ends "N passed, N failed")
#   make demo       render the README's first example
#   make gallery    render examples/*.csg into the contact sheet docs/gallery.png
#   make gallery-effects  render Fig. 6 of the seed (examples/effects/) into docs/fig6a..d.png
#   make deps       install the Debian packages the project needs (apt-get; sudo when not root)
#   make bench-ia   nanoseconds per interval operation, host and device, rigorous and fast
#   make bench      render the benchmark suite of issue 5 and write BENCHMARKS.md (BENCH_QUICK=1: a quick look;
#                   BRLCAD=DIR: rt of a BRL-CAD build beside iacsg on the BRL-CAD models)
#   make fuzz       libFuzzer on the expression compiler and the BRL-CAD reader, FUZZ_SECONDS each (default 60)
#   make install    PREFIX=/usr/local DESTDIR=: the command, libraries, headers, iacsg.pc, man pages, examples
#   make uninstall  removes what make install put there (same PREFIX and DESTDIR)
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
LIBS = -lOpenCL $(IMAGE_LIBS) -lnettle -lmpfr -lgmp -lm -lstdc++
CLI_LIBS = -lOpenCL -lnettle -lm -ldl -lpthread
LDFLAGS_ALL = $(OPT) $(LDFLAGS)

DEB_PACKAGES = gcc g++ make valgrind clang libclang-rt-14-dev pocl-opencl-icd ocl-icd-opencl-dev opencl-headers libopenimageio-dev nettle-dev libmpfr-dev \
               pkg-config groff-base libsdl2-dev xvfb xdotool openmpi-bin libopenmpi-dev

# OpenCL sources, in dependency order: they are concatenated (local #include lines dropped) into the binary.
IA_CL_HEADERS = ia/compat.h ia/round.h ia/interval.h ia/arith.h ia/elem.h ia/vec.h ia/vec_sincos.h
KERNEL_SOURCES ?= kernels/compat.h kernels/params.h kernels/camera.h kernels/packet_camera.h kernels/traverse.h \
                  kernels/packet.h kernels/tile_rays.h kernels/tile.h kernels/effects.h kernels/light.h kernels/shade.h \
                  kernels/render.cl kernels/march.h kernels/effects.cl
# The first-root program of an interpreted expression (src/render_expr.c): the tape interpreter, and the kernels
# without the effects' kernel and its march (march.h), which need a compiled expression (effects.h's types serve
# light.h).
TAPE_KERNEL_SOURCES = kernels/tape_eval.h $(filter-out kernels/march.h kernels/effects.cl,$(KERNEL_SOURCES))
# The segment path's program (src/render_scene.c): the same ia/ headers, the scene's solids, then these.
SCENE_KERNEL_SOURCES = kernels/compat.h kernels/params.h kernels/camera.h kernels/packet_camera.h kernels/traverse.h \
                       kernels/csg_node.h \
                       kernels/scene_data.h kernels/bvh.h kernels/prim_segments.h kernels/prim_pipe_segments.h \
                       kernels/segments_lanes.h kernels/segments_lanes_frame.h kernels/segments.h \
                       kernels/classify.h kernels/weave.h kernels/tile_rays.h kernels/surface.h kernels/scene_trace.h \
                       kernels/effects.h kernels/light.h kernels/packet.h kernels/tile.h kernels/scene_union.h \
                       kernels/march.h kernels/scene_rays.h kernels/scene_frame.h kernels/scene_lit.h kernels/render_scene.cl \
                       kernels/scene_effects.cl kernels/scene_centre.cl
# BRL-CAD's primitives and their table's layout, between the ia/ headers and the scene's solids (which call them).
PRIM_KERNEL_SOURCES = kernels/compat.h kernels/prim.h kernels/scene_prims.h
TEST_CL_SOURCES = $(sort $(wildcard tests/*.cl))

LIB_C = $(filter-out src/cli%.c,$(wildcard ia/*.c implicits/*.c src/*.c))
LIB_CXX = $(wildcard src/*.cpp)
CLI_C = $(wildcard src/cli*.c)
TEST_C = $(filter-out %_fp.c,$(wildcard tests/*.c))
TEST_FP_C = $(wildcard tests/*_fp.c)

LIB_OBJ = $(LIB_C:%.c=$(BUILD)/%.o) $(LIB_CXX:%.cpp=$(BUILD)/%.o) $(BUILD)/embedded_ia.o \
          $(if $(KERNEL_SOURCES),$(BUILD)/embedded_kernels.o $(BUILD)/embedded_tape_kernels.o) \
          $(BUILD)/embedded_scene_kernels.o \
          $(BUILD)/embedded_prim.o
CLI_OBJ = $(CLI_C:%.c=$(BUILD)/%.o)
TEST_OBJ = $(TEST_C:%.c=$(BUILD)/%.o) $(TEST_FP_C:%.c=$(BUILD)/%.f32.o) $(TEST_FP_C:%.c=$(BUILD)/%.f64.o) \
           $(if $(TEST_CL_SOURCES),$(BUILD)/embedded_tests.o)

.PHONY: all deps test check demo bench-ia fuzz clean bench gallery-effects
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

# The command is not linked with OpenImageIO: it loads libiacsg_image.so, beside it (installed: ../lib/iacsg/),
# in a child process (src/cli_writer.c), so that the ~180 ms of linking OpenImageIO's libraries overlap OpenCL's
# start.
$(BUILD)/iacsg: $(CLI_OBJ) $(BUILD)/image_deps.o $(BUILD)/libiacsg.a $(BUILD)/libiacsg_image.so $(BUILD)/libiacsg_mpi.so
	$(CC) $(LDFLAGS_ALL) -o $@ $(CLI_OBJ) $(BUILD)/image_deps.o $(BUILD)/libiacsg.a $(CLI_LIBS)

# `iacsg view` (src/cli_view*.c) loads SDL2 with dlopen (src/cli_view_sdl.h): only its headers are used here.
SDL_CFLAGS = $(shell pkg-config --cflags sdl2 2>/dev/null || echo -I/usr/include/SDL2)
$(BUILD)/src/cli_view.o $(BUILD)/src/cli_view_%.o: CFLAGS += $(SDL_CFLAGS)

$(BUILD)/libiacsg_image.so: $(BUILD)/pic/src/image_oiio.o $(BUILD)/pic/src/error.o
	$(CXX) $(LDFLAGS_ALL) -shared -o $@ $^ $(IMAGE_LIBS)
# Its shared libraries by soname, deepest first (ldd's order reversed), which the writer process loads one at a
# time before it (src/cli_writer.c: preload_dependencies). Empty where ldd is missing: then it loads them at once.
$(BUILD)/image_deps.c: $(BUILD)/libiacsg_image.so
	{ echo 'const char *const cli_image_deps[] = {'; ldd $< 2>/dev/null | awk '/=> \// {print "    \"" $$1 "\","}' | tac; \
	  echo '    0};'; } >$@

# The command's MPI layer, which it loads only under mpirun (src/cli_mpi.h): a plain render does not link MPI.
MPI_CFLAGS = $(shell mpicc --showme:compile 2>/dev/null)
MPI_LIBS = $(shell mpicc --showme:link 2>/dev/null)
$(BUILD)/pic/src/mpi/share.o: CFLAGS += $(MPI_CFLAGS)
$(BUILD)/libiacsg_mpi.so: $(BUILD)/pic/src/mpi/share.o
	$(CC) $(LDFLAGS_ALL) -shared -o $@ $^ $(MPI_LIBS) -lpthread

$(BUILD)/iacsg-tests: $(TEST_OBJ) $(BUILD)/libiacsg.a
	$(CC) $(LDFLAGS_ALL) -o $@ $(TEST_OBJ) $(BUILD)/libiacsg.a $(LIBS)

# The tests of C files as X(name) lines for tests/main.c's table (TEST_FP's: below).
LIST_TESTS = sed -n 's/^TEST(\([a-zA-Z0-9_]*\)).*/X(\1)/p'

# The compiler's tests alone (tests/t_fuzz_regressions.c), for valgrind's leak check (tests/run.sh), linked as the
# command is, without OpenImageIO: valgrind cannot always run its libraries' start-up (3.19 on an AMD EPYC stops
# with SIGILL at libhwy's rdtscp, before the first test).
$(BUILD)/compile-tests/tests.inc: tests/t_fuzz_regressions.c
	@mkdir -p $(dir $@)
	$(LIST_TESTS) $< > $@.tmp
	mv $@.tmp $@
$(BUILD)/compile-tests/main.o: tests/main.c $(BUILD)/compile-tests/tests.inc
	$(CC) -I$(BUILD)/compile-tests $(CFLAGS_ALL) $(TEST_MAIN_DEFS) -MMD -MP -c $< -o $@
$(BUILD)/iacsg-compile-tests: $(BUILD)/compile-tests/main.o $(BUILD)/tests/t_fuzz_regressions.o \
                              $(BUILD)/tests/expr_exercise.o $(BUILD)/libiacsg.a
	$(CC) $(LDFLAGS_ALL) -o $@ $^ $(CLI_LIBS)

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
TEST_MAIN_DEFS = -DIACSG_SOURCE_DIR_DEFAULT='"$(CURDIR)"' -DIACSG_BINARY_DEFAULT='"$(CURDIR)/$(BUILD)/iacsg"'
$(BUILD)/tests/main.o: CFLAGS += $(TEST_MAIN_DEFS)
$(BUILD)/tests.inc: $(TEST_C) $(TEST_FP_C)
	@mkdir -p $(dir $@)
	$(LIST_TESTS) $(TEST_C) > $@.tmp
	sed -n 's/^TEST_FP(\([a-zA-Z0-9_]*\)).*/X(\1_f32)\nX(\1_f64)/p' $(TEST_FP_C) >> $@.tmp
	mv $@.tmp $@

$(BUILD)/embed: src/tools/embed.c
	@mkdir -p $(dir $@)
	$(CC) -std=c11 $(WARN) -O1 -o $@ $<
$(BUILD)/embedded_ia.c: $(IA_CL_HEADERS) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_ia $(IA_CL_HEADERS) > $@
$(BUILD)/embedded_kernels.c: $(KERNEL_SOURCES) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_kernels $(KERNEL_SOURCES) > $@
$(BUILD)/embedded_tape_kernels.c: $(TAPE_KERNEL_SOURCES) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_tape_kernels $(TAPE_KERNEL_SOURCES) > $@
$(BUILD)/embedded_scene_kernels.c: $(SCENE_KERNEL_SOURCES) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_scene_kernels $(SCENE_KERNEL_SOURCES) > $@
$(BUILD)/embedded_prim.c: $(PRIM_KERNEL_SOURCES) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_prim $(PRIM_KERNEL_SOURCES) > $@
$(BUILD)/embedded_tests.c: $(TEST_CL_SOURCES) $(BUILD)/embed
	$(BUILD)/embed iacsg_cl_tests $(TEST_CL_SOURCES) > $@

# The user-facing targets install what is missing first, then build in a fresh make (so the new headers count).
# `make test` runs the suite, the suite under ASan+UBSan (build-asan/), and valgrind on the compiler
# (tests/run.sh); `make check` is the quick loop: the plain suite only.
test: deps
	@$(MAKE) --no-print-directory $(BUILD)/iacsg-tests $(BUILD)/iacsg-compile-tests $(BUILD)/iacsg installable
	@$(MAKE) --no-print-directory BUILD=build-asan SAN=1 build-asan/iacsg-tests build-asan/iacsg
	@BUILD=$(BUILD) ASAN_BUILD=build-asan tests/run.sh

check: $(BUILD)/iacsg-tests $(BUILD)/iacsg installable
	$(BUILD)/iacsg-tests

demo: deps
	@$(MAKE) --no-print-directory $(BUILD)/iacsg
	$(BUILD)/iacsg "min(sphere,torus)" -eps 1e-5

# The examples' scenes as one contact sheet, through the embedding example: the single expressions of Fig. 2, 3, 7
# and 8 of the Hijazi seed, then the scenes of regions and surfaces (the segment path; Fig. 5 among them).
SEGMENT_SCENES = examples/fig2_cube_sphere_regions.csg examples/machined_part.csg examples/icos.csg examples/sesc.csg
GALLERY_SCENES = $(sort $(filter-out $(SEGMENT_SCENES),$(wildcard examples/*.csg))) $(SEGMENT_SCENES)
$(BUILD)/examples/embed: examples/embed.c $(BUILD)/libiacsg.a $(BUILD)/include/iacsg.stamp
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -I$(BUILD)/include -o $@ $< $(BUILD)/libiacsg.a $(LIBS)
gallery: deps
	@$(MAKE) --no-print-directory $(BUILD)/examples/embed
	$(BUILD)/examples/embed docs/gallery.png 256 3 $(GALLERY_SCENES)

# Fig. 6 of the Hijazi seed, the ray-tracing effects (examples/effects/, README "Effects"): docs/fig6a..d.png.
FIG6 = examples/effects/fig6
gallery-effects: deps
	@$(MAKE) --no-print-directory $(BUILD)/iacsg
	$(BUILD)/iacsg $(FIG6)a_multiple_unions.csg -opacity 0.55 -reflect 0.35 -bounces 2 -size 360x360 -o docs/fig6a.png
	$(BUILD)/iacsg $(FIG6)b_decocube_sphere_blend.csg -shade gradient -size 360x360 -o docs/fig6b.png
	$(BUILD)/iacsg $(FIG6)c_bretzel_torus_shadows.csg -shadows -bounds -2.7,-2.1,-0.85,2.7,2.1,1.65 -size 360x360 \
	    -o docs/fig6c.png
	$(BUILD)/iacsg $(FIG6)d_tangle_torus_reflections.csg -reflect 0.6 -bounces 6 -shadows -size 360x360 -o docs/fig6d.png

bench-ia: deps
	@$(MAKE) --no-print-directory $(BUILD)/iacsg-tests
	$(BUILD)/iacsg-tests bench_ia

# Not part of `make test`: about 15 minutes (tests/bench/bench.sh says what it measures and how).
bench: deps
	@$(MAKE) --no-print-directory $(BUILD)/iacsg
	BENCH_QUICK=$(BENCH_QUICK) BENCH_BUILD=$(BUILD)/bench BRLCAD=$(BRLCAD) sh tests/bench/bench.sh $(BUILD)/iacsg

# libFuzzer over the lexer, parser and compiler, seeded from examples/ and tests/data/fuzz/. New crashes land in
# build-fuzz/crash-*: copy each into tests/data/fuzz/ so that every `make test` replays it.
FUZZ_SECONDS ?= 60
FUZZ_SRC = tests/fuzz/fuzz_expr.c tests/expr_exercise.c $(wildcard implicits/*.c) ia/decimal.c src/error.c src/clrt.c src/clrt_cache.c src/clrt_pocl.c src/detach.c src/digest.c src/version.c
build-fuzz/fuzz_expr: $(FUZZ_SRC) $(BUILD)/embedded_ia.c
	@mkdir -p $(dir $@)
	clang -std=c11 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -I. -Isrc \
	    -D_POSIX_C_SOURCE=200809L $^ -lOpenCL -lnettle -lm -o $@

# The BRL-CAD reader's target, seeded with the sample databases; its crashes go into tests/data/fuzz-brlcad/.
build-fuzz/fuzz_brlcad: tests/fuzz/fuzz_brlcad.c tests/brlcad_exercise.c $(filter-out tests/%,$(FUZZ_SRC)) $(BUILD)/embedded_ia.c
	@mkdir -p $(dir $@)
	clang -std=c11 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -I. -Isrc \
	    -D_POSIX_C_SOURCE=200809L $^ -lOpenCL -lnettle -lm -o $@

fuzz: deps
	@$(MAKE) --no-print-directory build-fuzz/fuzz_expr build-fuzz/fuzz_brlcad
	@mkdir -p build-fuzz/corpus build-fuzz/corpus-brlcad
	build-fuzz/fuzz_expr -max_total_time=$(FUZZ_SECONDS) -timeout=20 -rss_limit_mb=4096 -max_len=8192 \
	    -print_final_stats=1 -artifact_prefix=build-fuzz/ build-fuzz/corpus examples tests/data/fuzz
	build-fuzz/fuzz_brlcad -max_total_time=$(FUZZ_SECONDS) -timeout=20 -rss_limit_mb=4096 -max_len=65536 \
	    -print_final_stats=1 -artifact_prefix=build-fuzz/brlcad- build-fuzz/corpus-brlcad tests/data/brlcad \
	    tests/data/fuzz-brlcad

# ---- The library and command as installed software (issue 13) --------------------------------------------
# make install PREFIX=/usr/local DESTDIR= puts, under DESTDIR/PREFIX:
#   bin/iacsg                          the command (libiacsg.a linked in)
#   lib/libiacsg.so.VERSION            the shared library, SONAME libiacsg.so.MAJOR, links .so.MAJOR and .so
#   lib/libiacsg.a                     the static library
#   lib/iacsg/libiacsg_image.so        the command's image writer, found from bin/ as ../lib/iacsg/ (cli_writer.c)
#   lib/iacsg/libiacsg_mpi.so          the command's MPI layer, loaded the same way under mpirun (cli_job.c)
#   lib/pkgconfig/iacsg.pc             from src/iacsg.pc.in
#   include/iacsg/*.h                  PUBLIC_HEADERS, flat: #include <iacsg/iacsg.h>
#   share/man/man1/iacsg.1             made from `iacsg --help`, so the two say the same
#   share/man/man7/iacsg-language.7    made from docs/language.md
#   share/doc/iacsg/                   README.md and examples/
# make uninstall removes those files, then the directories they leave empty. tests/t_install.c checks both.
PREFIX ?= /usr/local
DESTDIR ?=
BINDIR = $(PREFIX)/bin
LIBDIR = $(PREFIX)/lib
INCLUDEDIR = $(PREFIX)/include
MANDIR = $(PREFIX)/share/man
DOCDIR = $(PREFIX)/share/doc/iacsg
IMAGE_HELPER_DIR = $(PREFIX)/lib/iacsg

# The public API: these headers, and nothing else, are installed (flat, under include/iacsg/) and exported.
PUBLIC_HEADERS = src/iacsg.h src/api.h src/error.h src/camera.h src/image.h src/render.h implicits/expr.h \
                 implicits/scene_api.h
EXAMPLES = $(sort $(wildcard examples/*.c examples/*.csg))

VERSION := $(shell sed -n 's/^\#define IACSG_VERSION "\(.*\)"$$/\1/p' src/iacsg.h 2>/dev/null)
SONAME = libiacsg.so.$(firstword $(subst ., ,$(VERSION)))
SHARED_LIB = $(BUILD)/libiacsg.so.$(VERSION)
PC_LIBS_PRIVATE = -lOpenCL $(IMAGE_LIBS) -lnettle -lstdc++ -lm
MAN_PAGES = $(BUILD)/man/iacsg.1 $(BUILD)/man/iacsg-language.7
INSTALLABLE = $(BUILD)/iacsg $(BUILD)/libiacsg.a $(BUILD)/libiacsg_image.so $(BUILD)/libiacsg_mpi.so $(SHARED_LIB) \
              $(BUILD)/include/iacsg.stamp $(MAN_PAGES)

.PHONY: installable install uninstall
all: installable
installable: $(INSTALLABLE)

# The shared library: position-independent objects (build/pic/) with hidden visibility, so that only the
# declarations of the public headers (between IACSG_API_BEGIN and IACSG_API_END, src/api.h) are exported;
# src/libiacsg.map also hides what OpenImageIO's headers mark default (its inline members).
PIC_OBJ = $(LIB_OBJ:$(BUILD)/%=$(BUILD)/pic/%)
$(BUILD)/pic/%.o: CFLAGS += -fvisibility=hidden
$(BUILD)/pic/%.o: CXXFLAGS += -fvisibility=hidden
$(BUILD)/pic/%.o: $(BUILD)/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -fPIC -c $< -o $@
$(SHARED_LIB): $(PIC_OBJ) src/libiacsg.map
	$(CXX) $(LDFLAGS_ALL) -shared -Wl,-soname,$(SONAME) -Wl,--version-script=src/libiacsg.map -Wl,-z,defs \
	    -o $@ $(PIC_OBJ) $(PC_LIBS_PRIVATE)

# The public headers as installed, flat, their quoted includes of one another reduced to the file name.
$(BUILD)/include/iacsg.stamp: $(PUBLIC_HEADERS) src/tools/public_headers.sh
	sh src/tools/public_headers.sh $(BUILD)/include/iacsg $(PUBLIC_HEADERS)
	@touch $@

$(BUILD)/man/iacsg.1: $(BUILD)/iacsg src/tools/help_to_man.awk
	@mkdir -p $(dir $@)
	$(BUILD)/iacsg --help | awk -v version=$(VERSION) -f src/tools/help_to_man.awk > $@.tmp && mv $@.tmp $@
$(BUILD)/man/iacsg-language.7: docs/language.md src/tools/md_to_man.awk
	@mkdir -p $(dir $@)
	awk -v name=iacsg-language -v section=7 -v version=$(VERSION) -f src/tools/md_to_man.awk docs/language.md \
	    > $@.tmp && mv $@.tmp $@

# Refused before anything is built or copied, in one line, when the prefix (or its nearest existing parent)
# cannot be written.
ifneq ($(filter install uninstall,$(MAKECMDGOALS)),)
INSTALL_ROOT_DENIED := $(shell d='$(DESTDIR)$(PREFIX)'; while [ ! -e "$$d" ]; do d=$$(dirname "$$d"); done; \
                               [ -w "$$d" ] || echo "$$d")
ifneq ($(INSTALL_ROOT_DENIED),)
$(error make $(filter install uninstall,$(MAKECMDGOALS)): no write access to $(INSTALL_ROOT_DENIED) \
    (PREFIX=$(PREFIX)); choose another PREFIX, or run it as root)
endif
endif

install: installable
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(IMAGE_HELPER_DIR) \
	    $(DESTDIR)$(INCLUDEDIR)/iacsg $(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(MANDIR)/man7 $(DESTDIR)$(DOCDIR)/examples
	install -m 755 $(BUILD)/iacsg $(DESTDIR)$(BINDIR)/
	install -m 755 $(SHARED_LIB) $(DESTDIR)$(LIBDIR)/
	ln -sf $(notdir $(SHARED_LIB)) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libiacsg.so
	install -m 644 $(BUILD)/libiacsg.a $(DESTDIR)$(LIBDIR)/
	install -m 755 $(BUILD)/libiacsg_image.so $(BUILD)/libiacsg_mpi.so $(DESTDIR)$(IMAGE_HELPER_DIR)/
	install -m 644 $(addprefix $(BUILD)/include/iacsg/,$(notdir $(PUBLIC_HEADERS))) \
	    $(DESTDIR)$(INCLUDEDIR)/iacsg/
	sed -e 's|@PREFIX@|$(PREFIX)|; s|@LIBDIR@|$(LIBDIR)|; s|@INCLUDEDIR@|$(INCLUDEDIR)|' \
	    -e 's|@VERSION@|$(VERSION)|; s|@LIBS_PRIVATE@|$(PC_LIBS_PRIVATE)|' src/iacsg.pc.in \
	    > $(DESTDIR)$(LIBDIR)/pkgconfig/iacsg.pc
	install -m 644 $(BUILD)/man/iacsg.1 $(DESTDIR)$(MANDIR)/man1/
	install -m 644 $(BUILD)/man/iacsg-language.7 $(DESTDIR)$(MANDIR)/man7/
	install -m 644 README.md $(DESTDIR)$(DOCDIR)/
	install -m 644 $(EXAMPLES) $(DESTDIR)$(DOCDIR)/examples/

# Standard directories (bin, lib, share/man, ...) go only when nothing else is left in them.
uninstall:
	rm -f $(DESTDIR)$(BINDIR)/iacsg $(DESTDIR)$(LIBDIR)/$(notdir $(SHARED_LIB)) \
	    $(DESTDIR)$(LIBDIR)/$(SONAME) $(DESTDIR)$(LIBDIR)/libiacsg.so $(DESTDIR)$(LIBDIR)/libiacsg.a \
	    $(DESTDIR)$(IMAGE_HELPER_DIR)/libiacsg_image.so $(DESTDIR)$(IMAGE_HELPER_DIR)/libiacsg_mpi.so \
	    $(DESTDIR)$(LIBDIR)/pkgconfig/iacsg.pc \
	    $(addprefix $(DESTDIR)$(INCLUDEDIR)/iacsg/,$(notdir $(PUBLIC_HEADERS))) \
	    $(DESTDIR)$(MANDIR)/man1/iacsg.1 $(DESTDIR)$(MANDIR)/man7/iacsg-language.7 \
	    $(DESTDIR)$(DOCDIR)/README.md $(addprefix $(DESTDIR)$(DOCDIR)/examples/,$(notdir $(EXAMPLES)))
	@for d in $(DOCDIR)/examples $(DOCDIR) $(PREFIX)/share/doc $(MANDIR)/man1 $(MANDIR)/man7 $(MANDIR) \
	    $(PREFIX)/share $(INCLUDEDIR)/iacsg $(INCLUDEDIR) $(IMAGE_HELPER_DIR) $(LIBDIR)/pkgconfig $(LIBDIR) \
	    $(BINDIR); do [ ! -d "$(DESTDIR)$$d" ] || rmdir --ignore-fail-on-non-empty "$(DESTDIR)$$d"; done

# tests/t_install.c installs this build (a sanitizer build's tests install the plain one, `build`).
$(BUILD)/tests/t_install.o: CFLAGS += -DIACSG_INSTALL_BUILD_DEFAULT='"$(if $(SAN),build,$(BUILD))"'

clean:
	rm -rf build build-asan build-fuzz

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
