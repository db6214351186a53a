SHELL := /bin/bash
# fieldloc - fixed-point field localization for legged soccer robots.
#
#   make            library build/libfieldloc.a and the host CLI build/fieldloc
#   make demo       the main job: a simulated walk through vision into the grid
#   make test       host unit and fixture tests; ends with "N passed, N failed"
#                   (suites spread over TEST_JOBS processes, default: the
#                   number of cores; the output is the serial run's order)
#   make check      firmware rules: strict C99 warnings as errors, no FP
#                   (-mgeneral-regs-only), no allocator symbols, fl_ prefix,
#                   no mutable file-scope state, allowed libc headers only;
#                   include layering, private _int.h headers, no include
#                   circles, no src/ function over 150 lines
#   make cross-test test suite under qemu-user for i686, mipsel and mips,
#                   output compared line by line with the host's
#   make test-exhaustive  the sweeps too long for every run (all uint32 isqrt)
#   make sanitize   test suite under ASan + UBSan (clang, integer checks too)
#   make bench      benchmarks, writes build/bench.tsv; callgrind counts
#                   (scanner; every localizer; the coach's frame:
#                   instructions per frame)
#   make perf       hot functions of the scanner (perf record)
#   make golden     rewrite fixtures/golden/ (expected detections)
#   make fuzz-smoke every libFuzzer harness for FUZZ_SECONDS (default 20)
#   make stack      worst-case stack depth of every public entry point
#   make valgrind   test suite (quick mode) under valgrind memcheck
#   make results    regenerate docs/RESULTS.md (tests, bench, walks, detection)
#   make install    PREFIX=/usr/local (DESTDIR too): headers, library,
#                   pkg-config file; the installed config.h has the build's
#                   option values as its defaults (CONFIG_DEFS below)
#   make echo       print the effective flags
#
# Variables: CC, BUILD (output folder), ARCHFLAGS (extra flags for every
# object, e.g. -static for cross builds), FW_NOFP (no-FP flag for src/),
# CONFIG_DEFS (overrides of include/fieldloc/config.h for the library and
# everything built with it, e.g. CONFIG_DEFS="-DFL_OBS_MAX=64"; a caller
# built with other values gets FL_ERR_CONFIG from every init, so install
# with `make install`, which writes these values into the installed
# config.h).

CC       ?= cc
AR       ?= ar
BUILD    ?= build
PREFIX   ?= /usr/local
ARCHFLAGS ?=
OPT      ?= -O2
CONFIG_DEFS ?=
# a command prefix that runs this build's executables (cross builds: the
# qemu-user of the target), for the tests that compile and run a caller
TEST_EXEC ?=
VERSION  := $(shell sed -n 's/^\#define FL_VERSION_STRING "\(.*\)"/\1/p' include/fieldloc/config.h)

WARN     = -std=c99 -pedantic -Wall -Wextra -Wconversion -Wshadow
MACHINE := $(shell $(CC) -dumpmachine 2>/dev/null)
ifneq ($(filter x86_64% i686% i386%,$(MACHINE)),)
FW_NOFP ?= -mgeneral-regs-only
endif
ifneq ($(filter i686% i386%,$(MACHINE)),)
# host-side doubles in SSE registers: no x87 excess precision in references
HOST_FP = -msse2 -mfpmath=sse
endif

FW_CFLAGS   = $(WARN) -Werror $(OPT) -g -fno-common -Iinclude $(FW_NOFP) $(ARCHFLAGS) $(CONFIG_DEFS)
HOST_CFLAGS = $(WARN) -Wno-address $(OPT) -g -Iinclude -Ihost_tests -Itools $(HOST_FP) $(ARCHFLAGS) $(CONFIG_DEFS) -D_DEFAULT_SOURCE $(CV_DEFS)
HOST_LIBS   = -lm

# OpenCV is optional and host-only: the tools' C++ files (tools/*/*.cpp: the
# OpenCV peers of the benchmarks; PNG output is tools/io/png.c, no library) are built only when
# pkg-config finds opencv4 and the build is native (not cross, not
# sanitize).  WITH_OPENCV=0 turns it off.
WITH_OPENCV ?= $(if $(ARCHFLAGS),0,1)
ifeq ($(WITH_OPENCV),1)
HAVE_OPENCV := $(shell pkg-config --exists opencv4 2>/dev/null && echo 1)
endif
ifeq ($(HAVE_OPENCV),1)
CXX      ?= g++
CV_DEFS   = -DFL_HAVE_OPENCV
CV_CFLAGS := $(shell pkg-config --cflags opencv4)
CV_LIBS   := $(filter-out -lopencv_%,$(shell pkg-config --libs opencv4)) -lopencv_imgproc -lopencv_core
# cv::ximgproc::thinning (opencv_contrib), the skeleton benchmark's peer,
# when that module's header is installed
ifneq ($(wildcard $(shell pkg-config --variable=includedir opencv4 2>/dev/null)/opencv2/ximgproc.hpp),)
CV_DEFS  += -DFL_HAVE_XIMGPROC
CV_LIBS  := $(CV_LIBS) -lopencv_ximgproc
endif
TOOL_CXX_SRC := $(sort $(wildcard tools/*/*.cpp))
endif
TOOL_CXX_OBJ := $(TOOL_CXX_SRC:%.cpp=$(BUILD)/%.o)

LINK      = $(if $(TOOL_CXX_OBJ),$(CXX),$(CC))

FW_SRC   := $(sort $(wildcard src/*/*.c))
FW_OBJ   := $(FW_SRC:%.c=$(BUILD)/%.o)
LIB      := $(BUILD)/libfieldloc.a

TEST_SRC := $(sort $(wildcard host_tests/*.c))
TEST_OBJ := $(TEST_SRC:%.c=$(BUILD)/%.o)
# Host tools by concern (tools/<folder>/, include order io <- world <- eval <-
# loc <- bench <- cli, no circles).  The test runner links every folder but
# cli/: no CLI command.
TOOL_DIRS    := io world eval loc bench
TOOL_LIB_SRC := $(sort $(foreach d,$(TOOL_DIRS),$(wildcard tools/$(d)/*.c)))
CLI_SRC      := $(sort $(wildcard tools/cli/*.c))
CLI_OBJ      := $(CLI_SRC:%.c=$(BUILD)/%.o)
TOOL_LIB_OBJ := $(TOOL_LIB_SRC:%.c=$(BUILD)/%.o) $(TOOL_CXX_OBJ)
CLI      := $(BUILD)/fieldloc
RUNNER   := $(BUILD)/run_tests

.PHONY: results demo perf golden fuzz-build fuzz-smoke stack valgrind fixtures all test test-quick test-exhaustive check cross-test sanitize bench install uninstall clean echo

all: $(LIB) $(CLI)

# Every object depends on a stamp of the effective flags, rewritten only when
# they change: installing OpenCV (or changing CC, OPT, ARCHFLAGS) after a build
# recompiles instead of linking objects built for another configuration.
FLAGS_STAMP := $(BUILD)/flags.txt
FLAGS_NOW   := $(CC) $(CXX) | $(FW_CFLAGS) | $(HOST_CFLAGS) | $(CV_CFLAGS) | $(CV_LIBS) | $(TEST_EXEC)
ifeq ($(filter clean echo,$(MAKECMDGOALS)),)
$(shell mkdir -p $(BUILD) && { [ "$$(cat $(FLAGS_STAMP) 2>/dev/null)" = "$(FLAGS_NOW)" ] || echo "$(FLAGS_NOW)" > $(FLAGS_STAMP); })
endif

$(BUILD)/src/%.o: src/%.c $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(FW_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/host_tests/%.o: host_tests/%.c $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(HOST_CFLAGS) -MMD -MP -c $< -o $@

# host_tests/test_config.c compiles callers at test time the way this
# build compiles (compiler, flags, library, how to run the result)
$(BUILD)/host_tests/test_config.o: HOST_CFLAGS += -DFL_TEST_CC='"$(CC)"' \
  -DFL_TEST_FLAGS='"$(ARCHFLAGS) $(CONFIG_DEFS)"' -DFL_TEST_ARCHFLAGS='"$(ARCHFLAGS)"' \
  -DFL_TEST_BUILD='"$(BUILD)"' -DFL_TEST_EXEC='"$(TEST_EXEC)"'

# The README example with its one localizer line changed to "mcl"
# (host_tests/test_example_swap.c): the rule fails unless exactly that one
# line differs, so the README's claim is what is tested.
SWAP_INC := $(BUILD)/gen/readme_example_mcl.inc
$(SWAP_INC): host_tests/readme_example.inc
	@mkdir -p $(dir $@)
	sed 's/^#define LOCALIZER "fuzzy" /#define LOCALIZER "mcl"   /' $< > $@.tmp
	@[ "$$(diff $< $@.tmp | grep -c '^>')" = 1 ] || { echo "$@: the LOCALIZER line was not found"; exit 1; }
	mv $@.tmp $@
$(BUILD)/host_tests/test_example_swap.o: $(SWAP_INC)
$(BUILD)/host_tests/test_example_swap.o: HOST_CFLAGS += -I$(BUILD)/gen

$(BUILD)/tools/%.o: tools/%.c $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(HOST_CFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/tools/%.o: tools/%.cpp $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CXX) -O2 -g -Wall -Iinclude -Itools $(CONFIG_DEFS) $(CV_DEFS) $(CV_CFLAGS) -MMD -MP -c $< -o $@

$(LIB): $(FW_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^

$(RUNNER): $(TEST_OBJ) $(TOOL_LIB_OBJ) $(LIB)
	$(LINK) $(HOST_CFLAGS) -o $@ $(TEST_OBJ) $(TOOL_LIB_OBJ) $(LIB) $(HOST_LIBS) $(CV_LIBS)

$(CLI): $(CLI_OBJ) $(TOOL_LIB_OBJ) $(LIB)
	$(LINK) $(HOST_CFLAGS) -o $@ $^ $(HOST_LIBS) $(CV_LIBS)

TEST_JOBS ?= $(shell nproc 2>/dev/null || echo 1)
test: $(RUNNER) $(CLI) check
	@$(RUNNER) -j $(TEST_JOBS) | tee $(BUILD)/test.log; exit $${PIPESTATUS[0]}

test-quick: $(RUNNER)
	@$(RUNNER) --quick -j $(TEST_JOBS)

test-exhaustive: $(RUNNER)
	@$(RUNNER) --exhaustive

check: $(LIB)
	@CC="$(CC)" BUILD="$(BUILD)" sh tools/build/check_firmware.sh

# Cross targets: the same sources with each cross compiler, statically
# linked, run under qemu-user with --quick (i686 directly when this kernel
# runs i386 binaries: the compiled code is the same, only faster), compared
# with the host's --quick output (lines starting with '#' carry host doubles
# and are not compared).  The runs go side by side (each is one process; the
# slowest of them sets the time).  The host run renders the tests' synthetic
# frames into RENDER_CACHE and the emulated runs read them
# (tools/world/render_cache.c): every target's firmware gets the same input
# bytes, and qemu skips the double-precision ray tracing that was most of its
# time.  The cache is emptied first, so no older renderer's frame survives.
CROSS_ARCHS ?= i686 mipsel mips
RENDER_CACHE = $(abspath $(BUILD))/render_cache
cross-test: $(RUNNER)
	@rm -rf $(RENDER_CACHE) && mkdir -p $(RENDER_CACHE)
	@FIELDLOC_RENDER_CACHE=$(RENDER_CACHE) $(RUNNER) --quick -j $(TEST_JOBS) | grep -v '^#' > $(BUILD)/quick-host.txt; \
	 for a in $(CROSS_ARCHS); do \
	   case $$a in i686) q=qemu-i386;; *) q=qemu-$$a;; esac; \
	   $(MAKE) --no-print-directory -s -j $(TEST_JOBS) BUILD=$(BUILD)/cross/$$a CC=$$a-linux-gnu-gcc \
	     AR=$$a-linux-gnu-ar ARCHFLAGS=-static TEST_EXEC=$$q $(BUILD)/cross/$$a/run_tests check || exit 1; \
	 done; \
	 for a in $(CROSS_ARCHS); do \
	   case $$a in i686) q=qemu-i386;; *) q=qemu-$$a;; esac; \
	   if [ $$a = i686 ] && $(BUILD)/cross/i686/run_tests -k fixed.angle_wrap >/dev/null 2>&1; then \
	     q=; echo "cross-test i686: runs natively (this x86-64 kernel executes i386 binaries)"; \
	   fi; \
	   ( FIELDLOC_RENDER_CACHE=$(RENDER_CACHE) $$q $(BUILD)/cross/$$a/run_tests --quick | grep -v '^#' > $(BUILD)/quick-$$a.txt ) & \
	 done; wait; \
	 status=0; \
	 for a in $(CROSS_ARCHS); do \
	   if cmp -s $(BUILD)/quick-host.txt $(BUILD)/quick-$$a.txt; then \
	     echo "cross-test $$a: identical to host ($$(tail -1 $(BUILD)/quick-$$a.txt))"; \
	   else \
	     echo "cross-test $$a: DIFFERS from host"; diff $(BUILD)/quick-host.txt $(BUILD)/quick-$$a.txt | head -20; status=1; \
	   fi; \
	 done; exit $$status

# The test suite under ASan + UBSan; the CLI is built the same way, so the
# cli.* tests run the sanitized tool too.
SAN_CC ?= clang
SAN_FLAGS = -fsanitize=address,undefined,integer -fno-sanitize=unsigned-integer-overflow,unsigned-shift-base -fno-sanitize-recover=all -fno-omit-frame-pointer
sanitize:
	@$(MAKE) --no-print-directory -j $(TEST_JOBS) BUILD=$(BUILD)/san CC=$(SAN_CC) OPT="-O1" \
	  ARCHFLAGS="$(SAN_FLAGS)" FW_NOFP= $(BUILD)/san/run_tests $(BUILD)/san/fieldloc
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 $(BUILD)/san/run_tests -j $(TEST_JOBS)

bench: $(CLI)
	@$(CLI) bench --out $(BUILD)/bench.tsv
	@sh tools/bench/callgrind.sh $(BUILD)
	@sh tools/bench/callgrind_loc.sh $(BUILD)
	@sh tools/bench/callgrind_coach.sh $(BUILD)

# The main job: a bundled simulated walk (spl2013, 130 s, head scanning, a
# kidnap and a penalty) rendered frame by frame, run through the vision path
# into the fuzzy grid; progress, the final error, and pictures in
# build/demo/ (PPM and PNG).  DEMO_ARGS="--seconds 70"
# gives a shorter run.
DEMO_ARGS ?=
demo: all
	@$(CLI) demo --out $(BUILD)/demo $(DEMO_ARGS)

# docs/RESULTS.md, generated (tools/build/results.sh); never edited by hand.
# make test runs first, inside the recipe (its own line, so that make -n
# runs nothing), so that the document states the time of the whole target.
results: $(CLI)
	@date +%s > $(BUILD)/results.start
	@$(MAKE) --no-print-directory test
	@RESULTS_START=$$(cat $(BUILD)/results.start) sh tools/build/results.sh $(BUILD) docs/RESULTS.md

# Hot functions of the column scanner under perf record.
perf: $(CLI)
	@sh tools/bench/perf.sh $(BUILD)

# Rewrite the expected detections of every fixture (fixtures/golden/) from
# the current vision path.  Only when asked: review the diff before committing.
golden: $(RUNNER)
	@FIELDLOC_WRITE_GOLDEN=1 $(RUNNER) -k features
	@FIELDLOC_WRITE_GOLDEN=1 $(RUNNER) -k walks
	@FIELDLOC_WRITE_GOLDEN=1 $(RUNNER) -k adversarial
	@FIELDLOC_WRITE_GOLDEN=1 $(RUNNER) -k scan.outputs_golden
	@FIELDLOC_WRITE_GOLDEN=1 $(RUNNER) -k scan.sparse_golden

# Regenerate the committed fixture set (deterministic: identical bytes on
# every run and machine).
fixtures: $(CLI)
	@$(CLI) fixtures --out fixtures

# Worst-case stack of every public entry point, from gcc's call-graph and
# stack-usage output (-fcallgraph-info=su) of the firmware as built.
stack:
	@rm -rf $(BUILD)/stack && mkdir -p $(BUILD)/stack
	@for f in $(FW_SRC); do \
	  $(CC) $(FW_CFLAGS) -fcallgraph-info=su -c $$f -o $(BUILD)/stack/$$(basename $$f .c).o \
	    -dumpbase $$(basename $$f .c) -dumpdir $(BUILD)/stack/ || exit 1; \
	done
	@python3 tools/build/stack_report.py --limit 4096 --indirect fl_loc_=src/loc/loc_ $(BUILD)/stack/*.ci

# The test suite under valgrind memcheck (quick mode: the sweeps are long).
# A plain host run renders the frames into RENDER_CACHE first and the run
# under valgrind reads them (as cross-test does): memcheck then spends its
# time on the firmware and the tests rather than on the ray tracer, which
# `make sanitize` checks (ASan + UBSan, the full suite, rendering included).
valgrind: $(RUNNER)
	@rm -rf $(RENDER_CACHE) && mkdir -p $(RENDER_CACHE)
	@FIELDLOC_RENDER_CACHE=$(RENDER_CACHE) $(RUNNER) --quick -j $(TEST_JOBS) > $(BUILD)/valgrind-host.txt || \
	  { tail -n 20 $(BUILD)/valgrind-host.txt; echo "valgrind: the host run that fills the frame cache failed"; exit 1; }
	FIELDLOC_RENDER_CACHE=$(RENDER_CACHE) valgrind --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite -q $(RUNNER) --quick -j $(TEST_JOBS)

# Fuzzing with libFuzzer (clang): one binary per host_tests/fuzz/fuzz_NAME.c,
# linked with the firmware and the host tools, ASan + UBSan.  fuzz-smoke runs
# each for FUZZ_SECONDS on a copy of its committed corpus
# (host_tests/fuzz/corpus/NAME); a crash leaves its input in build/fuzz/.
FUZZ_CC      ?= clang
FUZZ_SECONDS ?= 20
FUZZ_FLAGS    = -g -O1 -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all \
                -Iinclude -Itools -Ihost_tests -D_DEFAULT_SOURCE $(CONFIG_DEFS)
FUZZ_NAMES   := $(patsubst host_tests/fuzz/fuzz_%.c,%,$(wildcard host_tests/fuzz/fuzz_*.c))
FUZZ_LIB_SRC := $(FW_SRC) $(TOOL_LIB_SRC)
fuzz-build:
	@mkdir -p $(BUILD)/fuzz/obj
	@# an object is rebuilt when its source or any header is newer (a
	@# config.h change alters the fingerprint every init checks); objects
	@# and harnesses are built TEST_JOBS at a time
	@hdr=$$(ls -t include/fieldloc/*.h src/*/*.h tools/*/*.h | head -n 1); \
	for f in $(FUZZ_LIB_SRC); do \
	  o=$(BUILD)/fuzz/obj/$$(echo $$f | tr / _ | sed 's/\.c$$/.o/'); \
	  { [ $$o -nt $$f ] && [ $$o -nt $$hdr ]; } || echo "$$f $$o"; \
	done | xargs -r -n 2 -P $(TEST_JOBS) sh -c '$(FUZZ_CC) $(FUZZ_FLAGS) -c "$$0" -o "$$1"' || exit 1
	@printf '%s\n' $(FUZZ_NAMES) | xargs -n 1 -P $(TEST_JOBS) sh -c \
	  '$(FUZZ_CC) $(FUZZ_FLAGS) -fsanitize=fuzzer host_tests/fuzz/fuzz_$$0.c $(BUILD)/fuzz/obj/*.o -lm -o $(BUILD)/fuzz/fuzz_$$0' \
	  || exit 1
	@echo "fuzz: built $(FUZZ_NAMES)"

# The harnesses run TEST_JOBS at a time (each on its own core for
# FUZZ_SECONDS), then report in name order.
fuzz-smoke: fuzz-build
	@rm -f $(BUILD)/fuzz/rc_*; printf '%s\n' $(FUZZ_NAMES) | xargs -n 1 -P $(TEST_JOBS) sh -c \
	  'rm -rf $(BUILD)/fuzz/corpus_$$0; mkdir -p $(BUILD)/fuzz/corpus_$$0; \
	   cp host_tests/fuzz/corpus/$$0/* $(BUILD)/fuzz/corpus_$$0/ 2>/dev/null; \
	   $(BUILD)/fuzz/fuzz_$$0 -max_total_time=$(FUZZ_SECONDS) -rss_limit_mb=2048 \
	     -artifact_prefix=$(BUILD)/fuzz/crash_$$0- $(BUILD)/fuzz/corpus_$$0 \
	     > $(BUILD)/fuzz/log_$$0.txt 2>&1; echo $$? > $(BUILD)/fuzz/rc_$$0'; \
	 status=0; for n in $(FUZZ_NAMES); do \
	  if [ "$$(cat $(BUILD)/fuzz/rc_$$n 2>/dev/null)" = 0 ]; then \
	    echo "fuzz $$n: $$(grep -o 'Done [0-9]* runs' $(BUILD)/fuzz/log_$$n.txt), no crash"; \
	  else echo "fuzz $$n: CRASH (see $(BUILD)/fuzz/log_$$n.txt)"; tail -30 $(BUILD)/fuzz/log_$$n.txt; status=1; fi; \
	 done; exit $$status

# The installed config.h: the option defaults replaced by the values the
# library's objects were compiled with (tools/build/config_header.sh asks
# the compiler, with FW_CFLAGS).
INSTALL_CONFIG := $(BUILD)/install/config.h
$(INSTALL_CONFIG): include/fieldloc/config.h tools/build/config_header.sh $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	sh tools/build/config_header.sh include/fieldloc/config.h $(CC) $(FW_CFLAGS) > $@.tmp
	mv $@.tmp $@

install: $(LIB) $(INSTALL_CONFIG)
	install -d $(DESTDIR)$(PREFIX)/include/fieldloc $(DESTDIR)$(PREFIX)/lib/pkgconfig
	install -m 644 $(filter-out include/fieldloc/config.h,$(wildcard include/fieldloc/*.h)) $(DESTDIR)$(PREFIX)/include/fieldloc/
	install -m 644 $(INSTALL_CONFIG) $(DESTDIR)$(PREFIX)/include/fieldloc/config.h
	install -m 644 $(LIB) $(DESTDIR)$(PREFIX)/lib/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' tools/build/fieldloc.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/fieldloc.pc

uninstall:
	rm -rf $(DESTDIR)$(PREFIX)/include/fieldloc
	rm -f $(DESTDIR)$(PREFIX)/lib/libfieldloc.a $(DESTDIR)$(PREFIX)/lib/pkgconfig/fieldloc.pc

clean:
	rm -rf $(BUILD)

echo:
	@echo "CC          = $(CC) ($(MACHINE))"
	@echo "FW_CFLAGS   = $(FW_CFLAGS)"
	@echo "HOST_CFLAGS = $(HOST_CFLAGS)"
	@echo "VERSION     = $(VERSION)"

-include $(FW_OBJ:.o=.d) $(TEST_OBJ:.o=.d) $(TOOL_LIB_OBJ:.o=.d) $(CLI_OBJ:.o=.d)
