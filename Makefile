# haff: one non-recursive Makefile.  `make help` lists the targets.
# Sources are found by wildcard: a new file in a layer's folder (LAYERS below: engine/*/, db/,
# run/, analysis/, mc/, cli/) needs no edit here, and every tests/test_*.c is its own cmocka program.
.SUFFIXES:
.DEFAULT_GOAL := all
SHELL := /bin/bash

CC      ?= gcc
BUILD   ?= build
PKGS    := gsl sqlite3 inih
# Debian packages, by what needs them; each group has its stamp in $(BUILD)/ (below), so that
# building haff needs only the build's packages (a user without root and without, say, Slurm
# or chromium can still `make`).  The groups build on each other: demo's stamp needs build's,
# plots' demo's, test's plots'.  `make deps` installs them all (DEPS_PKGS).
# build: bin/haff, build/libhaff.so, the man page, the benchmarks, plots' shapes program
BUILD_PKGS := build-essential pkg-config libgsl-dev libsqlite3-dev libinih-dev
# demo: scenes/demo.sh queries the database with the sqlite3 shell
DEMO_PKGS := sqlite3
# plots: gnuplot draws; plots/scripts/*.py run on python3 (its standard library only)
PLOTS_PKGS := gnuplot-nox python3
# test: make test, make test-slurm, make fuzz and the test programs (cmocka)
TEST_PKGS := libcmocka-dev
# slurm-wlm, munge: tests/slurm/run.sh starts a one-node Slurm to test `haff sweep --slurm`
TEST_PKGS += slurm-wlm munge
# python3-pandas: tests/test_sql.c runs the pandas answers of docs/sql.md;
# groff-base: tests/test_unix.c formats the man page and fails on a troff warning
TEST_PKGS += python3-pandas groff-base
# python3-ase: tests/ase_check.py reads the XYZ export with ASE; ffmpeg: haff movie encodes
# (haff movie needs it, and gnuplot, when it runs; the build does not)
TEST_PKGS += python3-ase ffmpeg
# python3-gsd: tests/gsd_check.py reads `haff export gsd` with the real reader (gsd.hoomd);
# python3-numpy: the Python module python/haff (its tests run under make test)
TEST_PKGS += python3-gsd python3-numpy
# clang: make fuzz (libFuzzer on the parsers and the checkpoint restore)
TEST_PKGS += clang
# chromium: tests/test_plots.c loads make plots' report page (plots/out/index.html) headless
TEST_PKGS += chromium
DEPS_PKGS = $(BUILD_PKGS) $(DEMO_PKGS) $(PLOTS_PKGS) $(TEST_PKGS)
WARN    := -Wall -Wextra -Wshadow -Wconversion -Wno-sign-conversion -Wstrict-prototypes -Wmissing-prototypes
# Warnings are errors in CI (CI=true) and whenever WERROR=1.
ifneq ($(filter true 1,$(CI) $(WERROR)),)
WARN    += -Werror
endif
# -fno-math-errno: sqrt() is one instruction, without the call that would set errno for a
# negative argument (nothing here reads errno after a math function); +1.5 % for dimers, and
# the same results bit for bit
OPT     ?= -O2 -g -fno-math-errno
# Every object is position-independent, so that the same objects make build/libhaff.so;
# -fno-semantic-interposition keeps the calls inside the library direct (as without -fPIC);
# bench_engine, CPU seconds with and without (interleaved, one core, a loaded machine): disks
# 1000 at 0.45 1.59 +- 0.03 against 1.55 +- 0.02 (8 runs each), dimers 1000 at 0.30 8.61 +- 0.11
# against 8.59 +- 0.05 (3 runs): no difference beyond the noise (2 %)
PIC     ?= -fPIC -fno-semantic-interposition
# -ffp-contract=off: no fused multiply-add unless written (gcc's default under -std=c11, not
# clang's): the contact search's SSE2 safe steps (hd_body.c) and its scalar steps round alike
# on every compiler and -march
CFLAGS  := -std=c11 -D_GNU_SOURCE -pthread -ffp-contract=off $(OPT) $(PIC) $(WARN) -MMD -MP \
           $(shell pkg-config --cflags $(PKGS) 2>/dev/null) $(EXTRA_CFLAGS)
LDLIBS  := $(shell pkg-config --libs $(PKGS) 2>/dev/null || echo -lgsl -lgslcblas -lsqlite3 -linih) -lm -pthread
TESTLIBS:= -lcmocka

# --- layers --------------------------------------------------------------------------------
# The source folders are layers, lowest first (docs/architecture.md).  A layer's sources are
# compiled with the include path of their own layer and of the layers below (-I per folder),
# so an #include of a higher layer's header does not compile; tests/check-layers (make
# check-layers, part of make test) checks every #include "..." against the same order, also in
# headers that no source of their layer includes.  Tests, benchmarks and fuzzers see all.
LAYERS          := core body rods scene sim store run analysis mc tools
LAYER_core      := engine/core
LAYER_body      := engine/body
LAYER_rods      := engine/rods
LAYER_scene     := engine/scene
LAYER_sim       := engine/sim
LAYER_store     := db
LAYER_run       := run
LAYER_analysis  := analysis
LAYER_mc        := mc
LAYER_tools     := cli cli/analysis cli/mc
SRC_DIRS := $(foreach l,$(LAYERS),$(LAYER_$(l)))
LIB_DIRS := $(filter-out $(LAYER_tools),$(SRC_DIRS))
ALL_INC  := $(addprefix -I,$(SRC_DIRS))
_below   :=
$(foreach l,$(LAYERS),$(eval _below += $(LAYER_$(l)))$(eval INC_$(l) := $(addprefix -I,$(_below))))
$(foreach l,$(LAYERS),$(foreach d,$(LAYER_$(l)),$(eval $$(BUILD)/$(d)/%.o: LAYER_INC := $$(INC_$(l)))))

# Sources: every .c of the layer folders (the library) and of cli/ (the program).  A .c or .h
# elsewhere under engine/, db/, run/, analysis/, mc/ or cli/ belongs to no layer and is not built:
# said here, and an error of make check-layers.
LIB_SRC := $(wildcard $(addsuffix /*.c,$(LIB_DIRS)))
SRC_ROOTS := $(sort $(foreach d,$(SRC_DIRS),$(firstword $(subst /, ,$(d)))))
STRAY_SRC := $(filter-out $(addsuffix /%,$(SRC_DIRS)),$(wildcard $(foreach r,$(SRC_ROOTS),$(r)/*.[ch] $(r)/*/*.[ch])))
$(if $(STRAY_SRC),$(warning not in a layer folder (LAYERS), not built: $(STRAY_SRC)))
CLI_SRC := $(wildcard $(addsuffix /*.c,$(LAYER_tools)))
TEST_SRC:= $(wildcard tests/test_*.c)
LIB_OBJ := $(LIB_SRC:%.c=$(BUILD)/%.o) $(BUILD)/gen/schema_sql.o $(BUILD)/gen/version.o
CLI_OBJ := $(CLI_SRC:%.c=$(BUILD)/%.o)
TEST_BIN:= $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
LIB     := $(BUILD)/libhaff.a
SOLIB   := $(BUILD)/libhaff.so
BUILD_STAMP := $(BUILD)/.deps-build
DEMO_STAMP  := $(BUILD)/.deps-demo
PLOTS_STAMP := $(BUILD)/.deps-plots
TEST_STAMP  := $(BUILD)/.deps-test

.PHONY: all deps test test-unit check-layers fuzz demo bench plots clean help format install uninstall scene-keys schema
all: bin/haff $(SOLIB) $(BUILD)/haff.1

help:
	@echo "make deps    install missing Debian packages (run by the other targets as needed)"
	@echo "make         build bin/haff"
	@echo "make test    build and run every test (then an ASan+UBSan build), one summary line"
	@echo "make check-layers  no source includes a header of a higher layer (part of make test)"
	@echo "make test-slurm  the Slurm test alone (a one-node Slurm started and stopped for it)"
	@echo "make fuzz    libFuzzer on the parsers (tests/fuzz/fuzz_*.c), FUZZ_TIME s each"
	@echo "make demo    run the demo scene and print what it logged"
	@echo "make scene-keys  rewrite the key tables of docs/scene-keys.md from the key table"
	@echo "make schema  rewrite the collisions table of db/schema.sql from its column table"
	@echo "make bench   benchmarks -> bench/results.md"
	@echo "make plots   the papers' figures (PNG, SVG, PDF) and tables -> plots/out/, all on plots/out/index.html"
	@echo "make install PREFIX=/usr/local DESTDIR=   bin/haff, man page haff(1), bash completion,"
	@echo "             the docs in PREFIX/share/doc/haff (DOCDIR), the Python module haff (PYTHONDIR)"
	@echo "make uninstall PREFIX=... DESTDIR=...      removes what make install put there"

# --- dependencies --------------------------------------------------------------------------
# deps_install(PACKAGES,WHAT): the missing ones of the Debian PACKAGES installed (as root), or
# the apt-get command that would install them printed and an error (otherwise); WHAT says what
# needs them.
define deps_install
missing=""; for p in $(1); do \
  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; done; \
if [ -z "$$missing" ]; then exit 0; fi; \
if [ "$$(id -u)" != 0 ]; then echo "deps: missing$(if $(2), for $(2)):$$missing"; \
  echo "deps: run: sudo apt-get install -y$$missing"; exit 1; fi; \
echo "deps: installing$$missing"; \
apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing >/dev/null
endef

deps:
	@$(call deps_install,$(DEPS_PKGS),)
	@echo "deps: all present"
	@mkdir -p $(BUILD) && touch $(BUILD_STAMP) $(DEMO_STAMP) $(PLOTS_STAMP) $(TEST_STAMP)

$(BUILD_STAMP):
	@$(call deps_install,$(BUILD_PKGS),building haff)
	@mkdir -p $(@D) && touch $@
$(DEMO_STAMP): | $(BUILD_STAMP)
	@$(call deps_install,$(DEMO_PKGS),make demo)
	@touch $@
$(PLOTS_STAMP): | $(DEMO_STAMP)
	@$(call deps_install,$(PLOTS_PKGS),make plots)
	@touch $@
$(TEST_STAMP): | $(PLOTS_STAMP)
	@$(call deps_install,$(TEST_PKGS),the tests)
	@touch $@

# --- build ---------------------------------------------------------------------------------
$(BUILD)/%.o: %.c | $(BUILD_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LAYER_INC) -c $< -o $@

# db/schema.sql is compiled into the binary as a string (hd_schema_sql).
$(BUILD)/gen/schema_sql.c: db/schema.sql
	@mkdir -p $(@D)
	@{ echo '/* generated from db/schema.sql by the Makefile: do not edit */'; \
	   echo 'extern const char hd_schema_sql[];'; echo 'const char hd_schema_sql[] ='; \
	   sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/^/  "/' -e 's/$$/\\n"/' $<; echo ';'; } > $@
$(BUILD)/gen/schema_sql.o: $(BUILD)/gen/schema_sql.c | $(BUILD_STAMP)
	$(CC) $(CFLAGS) -c $< -o $@

# The build's provenance, compiled in (engine/core/hd_build.h; runs.git_commit ... runs.cflags,
# `haff -V`): the commit (git rev-parse HEAD), whether the tree differs from it (a tracked file
# modified, or an untracked file in a source folder, which the wildcards would build), the
# compiler and the flags.  Written while make reads this file, and only when it changes, so that
# `make` stays incremental and `make -q` answers.  Outside a git work tree of this very folder
# (a tarball, even one unpacked inside another repository): commit 'unknown', dirty -1.
GIT_TOP   := $(shell git -C $(CURDIR) rev-parse --show-toplevel 2>/dev/null)
ifeq ($(GIT_TOP),$(CURDIR))
GIT_COMMIT := $(shell git -C $(CURDIR) rev-parse HEAD 2>/dev/null)
GIT_DESCR  := $(shell git -C $(CURDIR) describe --always --dirty 2>/dev/null)
GIT_DIRTY  := $(if $(strip $(shell git -C $(CURDIR) status --porcelain --untracked-files=no \
                2>/dev/null; git -C $(CURDIR) status --porcelain -- $(SRC_DIRS) 2>/dev/null)),1,0)
endif
GIT_COMMIT := $(or $(GIT_COMMIT),unknown)
GIT_DESCR  := $(or $(GIT_DESCR),unknown)
GIT_DIRTY  := $(or $(GIT_DIRTY),-1)
BUILD_CC    := $(shell $(CC) --version 2>/dev/null | head -1)
BUILD_FLAGS := $(strip $(filter-out -MMD -MP,$(CFLAGS)))
# C string literal of $(1): backslashes and double quotes escaped
c_str = "$(subst ",\",$(subst \,\\,$(1)))"
define VERSION_C
/* generated by the Makefile: the build's provenance (engine/core/hd_build.h) */
const char hd_build_commit[] = $(call c_str,$(GIT_COMMIT));
const char hd_build_describe[] = $(call c_str,$(GIT_DESCR));
const int hd_build_dirty = $(GIT_DIRTY);
const char hd_build_compiler[] = $(call c_str,$(BUILD_CC));
const char hd_build_cflags[] = $(call c_str,$(BUILD_FLAGS));
endef
$(shell mkdir -p $(BUILD)/gen)
$(file >$(BUILD)/gen/version.c.new,$(VERSION_C))
$(shell cmp -s $(BUILD)/gen/version.c.new $(BUILD)/gen/version.c && rm -f $(BUILD)/gen/version.c.new \
  || mv -f $(BUILD)/gen/version.c.new $(BUILD)/gen/version.c)
$(BUILD)/gen/version.o: $(BUILD)/gen/version.c | $(BUILD_STAMP)
	$(CC) $(CFLAGS) $(INC_core) -include hd_build.h -c $< -o $@

$(LIB): $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

bin/haff: $(CLI_OBJ) $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -o $@ $(CLI_OBJ) $(LIB) $(LDLIBS)

# The library as a shared object, from the same (position-independent) objects.
$(SOLIB): $(LIB_OBJ)
	$(CC) $(CFLAGS) -shared -o $@ $^ $(LDLIBS)

# The man page, made from the binary's own help texts (cli/haff-man.sh), so it cannot drift; it
# names DOCDIR (below) as where the documentation is (make install writes it again for its own).
$(BUILD)/haff.1: bin/haff cli/haff-man.sh
	@mkdir -p $(@D)
	cli/haff-man.sh bin/haff $(DOCDIR) > $@.tmp && mv $@.tmp $@

# Every test links the library and the subcommands (all the CLI's objects but the one with
# main()): tests call subcommands' mains (hd_cmd_haff_fit, ...) and test_cli_tables checks the
# table of subcommands (cli/haff_commands.c) and every option table.
CLI_CMD_OBJ := $(filter-out $(BUILD)/cli/haff.o,$(CLI_OBJ))
$(BUILD)/tests/%: tests/%.c $(CLI_CMD_OBJ) $(LIB) | $(TEST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(ALL_INC) -Itests -o $@ $< $(CLI_CMD_OBJ) $(LIB) $(LDLIBS) $(TESTLIBS)

# --- tests ---------------------------------------------------------------------------------
# Each test program is a cmocka group; tests/run-tests sums their results into one line
# "N passed, N failed" and exits non-zero on any failure.  The ASan+UBSan build of the same
# tests runs after (HAFF_SANITIZE=1 lets long physics tests shrink their sizes there).
.PHONY: test-slurm
test-unit: $(TEST_BIN) bin/haff
	@HAFF_BIN=$(CURDIR)/bin/haff tests/run-tests $(TEST_BIN)

test: | $(TEST_STAMP)
	@$(MAKE) --no-print-directory all $(TEST_BIN)
	@$(MAKE) --no-print-directory BUILD=build-asan \
	  OPT="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=undefined,float-cast-overflow" \
	  $(patsubst $(BUILD)/%,build-asan/%,$(TEST_BIN))
	@HAFF_BIN=$(CURDIR)/bin/haff HAFF_LAYERS="$(LAYER_SPEC)" tests/run-tests \
	  $(TEST_BIN) $(SLURM_TEST) tests/check-layers -- $(patsubst $(BUILD)/%,build-asan/%,$(TEST_BIN))

# The layer order checked on the sources' #include lines: tests/check-layers reads the layers'
# folders from HAFF_LAYERS, lowest first, layers separated by ":".
LAYER_SPEC := $(strip $(foreach l,$(LAYERS),: $(LAYER_$(l))))
check-layers:
	@HAFF_LAYERS="$(LAYER_SPEC)" tests/check-layers

# A real one-node Slurm (munged, slurmctld, slurmd started and stopped by the script): a sweep
# as a job array, a task stopped with SIGTERM, resumed, merged.  Part of `make test`, ~40 s.
SLURM_TEST := tests/slurm/run.sh
test-slurm: bin/haff | $(TEST_STAMP)
	@HAFF_BIN=$(CURDIR)/bin/haff tests/run-tests $(SLURM_TEST)

# --- fuzzing -------------------------------------------------------------------------------
# libFuzzer (Debian's clang) on every tests/fuzz/fuzz_NAME.c, against the library built with
# clang, ASan and UBSan in build-fuzz/.  Seeds: tests/fuzz/corpus/NAME/ (read only); the inputs
# it finds and any crash file go to build-fuzz/ only.  A fixed seed and run count, each target
# bounded by FUZZ_TIME seconds.  A crash it finds is kept as a cmocka regression test.  Warnings
# are not errors here: gcc's build (make test) is the gate, clang warns about other things.
FUZZ_SRC  := $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_BIN  := $(FUZZ_SRC:tests/fuzz/%.c=build-fuzz/tests/fuzz/%)
FUZZ_TIME ?= 20
FUZZ_RUNS ?= 1000000
FUZZ_SAN  := -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all

fuzz: | $(TEST_STAMP)
	@$(MAKE) --no-print-directory BUILD=build-fuzz CC=clang CI= WERROR= \
	  OPT="-O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link $(FUZZ_SAN)" $(FUZZ_BIN)
	@for b in $(FUZZ_BIN); do name=$${b##*/fuzz_}; mkdir -p build-fuzz/corpus/$$name; \
	  seeds=tests/fuzz/corpus/$$name; [ -d $$seeds ] || seeds=; \
	  if ! $$b -seed=1 -runs=$(FUZZ_RUNS) -max_total_time=$(FUZZ_TIME) -timeout=10 \
	      -rss_limit_mb=2048 -artifact_prefix=build-fuzz/$$name- build-fuzz/corpus/$$name \
	      $$seeds > build-fuzz/$$name.log 2>&1; then \
	    tail -40 build-fuzz/$$name.log; echo "fuzz $$name: FAILED (build-fuzz/$$name.log)"; exit 1; fi; \
	  echo "fuzz $$name: $$(grep -E '^#[0-9]+' build-fuzz/$$name.log | tail -1)"; done

build-fuzz/tests/fuzz/%: tests/fuzz/%.c $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(ALL_INC) -fsanitize=fuzzer -Itests -o $@ $< $(LIB) $(LDLIBS)

# --- user targets --------------------------------------------------------------------------
# The key tables of docs/scene-keys.md come from the scene key table (engine/scene/hd_scene_keys.h);
# tests/test_scene.c fails when they differ.
scene-keys: $(BUILD)/tests/gen_scene_keys
	@$< docs/scene-keys.md

# The CREATE TABLE of collisions in db/schema.sql comes from the column table (db/hd_db.h,
# HD_COLLISION_COLUMNS); tests/test_db.c fails when they differ.
schema: $(BUILD)/tests/gen_schema
	@$< db/schema.sql

demo: bin/haff | $(DEMO_STAMP)
	@scenes/demo.sh

BENCH_BIN := $(BUILD)/bench/bench_engine
$(BENCH_BIN): bench/bench_engine.c $(LIB) | $(BUILD_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(ALL_INC) -o $@ $< $(LIB) $(LDLIBS)

BENCH_RODS_BIN := $(BUILD)/bench/bench_rods
$(BENCH_RODS_BIN): bench/bench_rods.c $(LIB) | $(BUILD_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(ALL_INC) -o $@ $< $(LIB) $(LDLIBS)

MEMLAT_BIN := $(BUILD)/bench/memlat
$(MEMLAT_BIN): bench/memlat.c | $(BUILD_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -o $@ $< $(LDLIBS)

bench: bin/haff $(BENCH_BIN) $(MEMLAT_BIN)
	@BENCH_BIN=$(BENCH_BIN) MEMLAT_BIN=$(MEMLAT_BIN) bench/run.sh

SHAPES_BIN := $(BUILD)/plots/shapes
$(SHAPES_BIN): plots/shapes.c $(LIB) | $(BUILD_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(ALL_INC) -o $@ $< $(LIB) $(LDLIBS)

plots: bin/haff $(SHAPES_BIN) | $(PLOTS_STAMP)
	@$(MAKE) --no-print-directory -f plots/plots.mk SHAPES_BIN=$(SHAPES_BIN)

format:
	clang-format -i $(LIB_SRC) $(CLI_SRC) $(TEST_SRC) $(wildcard */*.h */*/*.h)

# --- install -------------------------------------------------------------------------------
# bin/haff, the man page haff(1), the bash completion and the documentation (DOCDIR: README.md,
# docs/, db/README.md, the schema and the example queries, in the source tree's layout so that
# their links hold); the man page names DOCDIR.
PREFIX  ?= /usr/local
BINDIR  ?= $(PREFIX)/bin
MANDIR  ?= $(PREFIX)/share/man
DOCDIR  ?= $(PREFIX)/share/doc/haff
BASHCOMPDIR ?= $(PREFIX)/share/bash-completion/completions
DOC_FILES := README.md $(wildcard docs/*.md) db/README.md db/schema.sql $(wildcard db/queries/*.sql)
# The Python module python/haff, where Debian's /usr/bin/python3 finds it: /usr/lib/python3/
# dist-packages for PREFIX=/usr, PREFIX/lib/python3.X/dist-packages otherwise (/usr/local is on
# its path; another PREFIX needs PYTHONPATH).
PYVER   := $(shell /usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null)
PYTHONDIR ?= $(if $(filter /usr,$(PREFIX)),$(PREFIX)/lib/python3/dist-packages,$(PREFIX)/lib/python$(PYVER)/dist-packages)
INSTALLED := $(DESTDIR)$(BINDIR)/haff $(DESTDIR)$(MANDIR)/man1/haff.1 \
             $(DESTDIR)$(BASHCOMPDIR)/haff $(addprefix $(DESTDIR)$(DOCDIR)/,$(DOC_FILES)) \
             $(DESTDIR)$(PYTHONDIR)/haff/__init__.py

install: bin/haff cli/haff-man.sh
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(BASHCOMPDIR) \
	  $(sort $(dir $(addprefix $(DESTDIR)$(DOCDIR)/,$(DOC_FILES))))
	install -m 755 bin/haff $(DESTDIR)$(BINDIR)/haff
	cli/haff-man.sh bin/haff $(DOCDIR) > $(BUILD)/haff-install.1
	install -m 644 $(BUILD)/haff-install.1 $(DESTDIR)$(MANDIR)/man1/haff.1
	install -m 644 cli/haff-completion.bash $(DESTDIR)$(BASHCOMPDIR)/haff
	for f in $(DOC_FILES); do install -m 644 $$f $(DESTDIR)$(DOCDIR)/$$f || exit 1; done
	install -d $(DESTDIR)$(PYTHONDIR)/haff
	install -m 644 python/haff/__init__.py $(DESTDIR)$(PYTHONDIR)/haff/__init__.py

# removes what make install put there, and DOCDIR's folders once they are empty
uninstall:
	rm -f $(INSTALLED)
	-rmdir $(addprefix $(DESTDIR)$(DOCDIR)/,docs db/queries db) $(DESTDIR)$(DOCDIR) 2>/dev/null
	rm -rf $(DESTDIR)$(PYTHONDIR)/haff

clean:
	rm -rf build build-asan build-fuzz bin

-include $(wildcard $(BUILD)/*/*.d $(BUILD)/*/*/*.d $(BUILD)/*/*/*/*.d)
