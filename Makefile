# flexmech: nonlinear analysis and optimal design of flexible mechanisms.
#
#   make run     build and run the default deck (prints where the output went)
#   make check   the fast inner loop: unit suites and a representative set of decks
#   make test    build (release and debug), run unit, deck-error and regression tests
#   make check-docs  run the tutorial's commands and check the numbers it quotes
#   make bench   work-precision and cost studies (figures, not pass/fail)
#   make plot OUT=run.out   standard figures of an output (PNG, SVG; flexmech plot)
#   make figures            the paper gallery (doc/gallery.md, doc/figures/gallery/)
#   make MPI=1   build/mpi/bin/flexmech: sweeps and batches shared by MPI ranks (Open MPI)
#   make NATIVE=1  build/native/bin/flexmech: -O3 -march=native for this CPU (not portable)
#   make bench-peers  flexmech against Exudyn (pip, in build/peers/venv): CPU at equal accuracy
#   make deps    install missing system packages and fetch ODEPACK (done by every target)
#
# Our own code builds with -std=f2008 -Wall -Wextra, warning-free.  ODEPACK is
# compiled from Debian's octave source package with its own legacy flags.
#
# Builds and test runs use every core (make -jN overrides); each build step's
# output goes to build/<flavour>/build.log and a failing step prints its own
# output.  V=1 prints every command line instead.

# -j for the top-level make only: sub-makes share its job slots.
ifeq ($(MAKELEVEL),0)
MAKEFLAGS += -j$(shell nproc 2>/dev/null || echo 1)
endif
# one identifier per top-level make, so that a build prints its banner once
ifndef BUILD_ID
export BUILD_ID := $(shell date +%s%N)
endif
V ?=

FC        ?= gfortran
ifeq ($(origin FC),default)
FC        := gfortran
endif
BUILD     ?= release
# MPI=1: Open MPI's mpif90, src/batch/mpi/job_pool.f90 instead of the serial
# pool, objects in build/<flavour>-mpi, the program in build/mpi/bin.
MPI       ?=
ifeq ($(MPI),1)
FC        := mpif90
MPI_PKGS  := libopenmpi-dev openmpi-bin
POOL_SKIP := src/batch/serial/*
FLAVOUR   := $(BUILD)-mpi
else
POOL_SKIP := src/batch/mpi/*
FLAVOUR   := $(BUILD)
endif
# NATIVE=1: -O3 -march=native for this machine's CPU (doc/benchmarks.md, "Speed
# at equal accuracy"), objects in build/<flavour>-native, the program in
# build/native/bin; the default build stays portable.
NATIVE    ?=
ifeq ($(NATIVE),1)
FLAVOUR   := $(FLAVOUR)-native
endif
BUILD_DIR := build
ODEPACK_SRC ?= $(BUILD_DIR)/odepack/src
DECK      ?= inputs/fourbar_150_damped.nml
LIBS      := -llapack -lblas

WARN      := -std=f2008 -Wall -Wextra -Wimplicit-interface -fimplicit-none
FFLAGS_release := -O2 -g $(WARN)
FFLAGS_debug   := -O0 -g $(WARN) -fcheck=all -ffpe-trap=invalid,zero,overflow -fbacktrace
LEGACY_FFLAGS  := -O2 -g -std=legacy -w

ifeq ($(NATIVE),1)
FFLAGS_release := -O3 -march=native -g $(WARN)
endif
FFLAGS    := $(FFLAGS_$(BUILD))
OUT       := $(BUILD_DIR)/$(FLAVOUR)
# `make plot OUT=run.out` names an output file; the build directory keeps its name.
ifeq ($(origin OUT),command line)
PLOT_OUTPUT := $(OUT)
override OUT := $(BUILD_DIR)/$(FLAVOUR)
endif
OBJ_DIR   := $(OUT)/obj
MOD_DIR   := $(OUT)/mod
BUILD_LOG := $(OUT)/build.log
# $(call step,BANNER,COMMAND[,LOG]): COMMAND, quiet unless V=1, its output
# in LOG (default BUILD_LOG; tools/build_step.sh)
ifeq ($(V),1)
step = $(2)
else
step = @sh tools/build_step.sh $(or $(3),$(BUILD_LOG)) '$(1)' $(2)
endif
COMPILING := flexmech: compiling the $(FLAVOUR) build in $(OUT)
BIN_DIR   := $(if $(filter release,$(BUILD)),$(if $(filter 1,$(MPI)),$(BUILD_DIR)/mpi/bin,$(BUILD_DIR)/bin),$(OUT)/bin)
ifeq ($(NATIVE),1)
BIN_DIR   := $(if $(filter release,$(BUILD)),$(BUILD_DIR)/native$(if $(filter 1,$(MPI)),-mpi)/bin,$(OUT)/bin)
endif

LIB_SRC   := $(sort $(shell find src -name '*.f90' ! -path 'src/app/*' ! -path '$(POOL_SKIP)'))
APP_SRC   := src/app/flexmech.f90
TLIB_SRC  := $(sort $(wildcard tests/lib/*.f90))
TEST_SRC  := $(sort $(wildcard tests/unit/test_*.f90))
TOOL_SRC  := $(sort $(wildcard tests/tools/*.f90))
BENCH_SRC := $(sort $(wildcard bench/*.f90))
ALL_SRC   := $(LIB_SRC) $(APP_SRC) $(TLIB_SRC) $(TEST_SRC) $(TOOL_SRC) $(BENCH_SRC)

obj = $(addprefix $(OBJ_DIR)/,$(notdir $(1:.f90=.o)))
LIB_OBJ   := $(call obj,$(LIB_SRC))
TLIB_OBJ  := $(call obj,$(TLIB_SRC))
TEST_BIN  := $(addprefix $(OUT)/tests/,$(notdir $(TEST_SRC:.f90=)))
TOOL_BIN  := $(addprefix $(OUT)/tools/,$(notdir $(TOOL_SRC:.f90=)))
BENCH_BIN := $(addprefix $(OUT)/bench/,$(notdir $(BENCH_SRC:.f90=)))

# DPREPJ and DSOLSY (DLSODE's Newton matrix) are ours: src/ode/lsode_newton.f90.
ODEPACK_FILES := dlsode dstode dintdy dcfode dewset dvnorm
ODEPACK_LIB   := $(BUILD_DIR)/odepack/libodepack.a
ODEPACK_LIST  := $(BUILD_DIR)/odepack/files.txt

vpath %.f90 $(sort $(dir $(ALL_SRC)))

.PHONY: all deps odepack run test test-bins bench bench-peers clean distclean help plot figures \
        test-bins-release test-bins-debug mpi-if-present
.DEFAULT_GOAL := all

all: $(BIN_DIR)/flexmech

help:
	@sed -n '3,13p' Makefile

# ---------------------------------------------------------------- dependencies
deps:
	@DEPS_LOG=$(BUILD_DIR)/deps.log sh tools/install_deps.sh $(EXTRA_PKGS) $(MPI_PKGS)

$(ODEPACK_SRC)/dlsode.f: | deps
	@sh tools/fetch_odepack.sh $(BUILD_DIR) $(ODEPACK_SRC)

odepack: $(ODEPACK_LIB)

# The file list is rewritten only when it changes, so that the library is rebuilt then.
$(shell mkdir -p $(BUILD_DIR)/odepack; echo '$(ODEPACK_FILES)' | cmp -s - $(ODEPACK_LIST) || echo '$(ODEPACK_FILES)' > $(ODEPACK_LIST))

$(ODEPACK_LIB): $(ODEPACK_SRC)/dlsode.f $(ODEPACK_LIST)
	@mkdir -p $(BUILD_DIR)/odepack/obj
	$(if $(filter 1,$(V)),,@sh tools/build_step.sh $(BUILD_DIR)/odepack/build.log 'flexmech: compiling ODEPACK') \
	  sh -c 'for f in $(ODEPACK_FILES); do $(FC) $(LEGACY_FFLAGS) -c $(ODEPACK_SRC)/$$f.f -o $(BUILD_DIR)/odepack/obj/$$f.o || exit 1; done'
	@rm -f $@ && ar rcs $@ $(addprefix $(BUILD_DIR)/odepack/obj/,$(addsuffix .o,$(ODEPACK_FILES)))
	@echo "built $@ from $(ODEPACK_SRC)"

# ---------------------------------------------------------------- compilation
# The source list is rewritten only when it changes, so that adding, moving or
# removing a file regenerates the module dependencies.
SRC_LIST := $(OUT)/sources.txt
$(shell mkdir -p $(OUT); echo '$(ALL_SRC)' | cmp -s - $(SRC_LIST) || echo '$(ALL_SRC)' > $(SRC_LIST))

$(OUT)/deps.mk: $(ALL_SRC) $(SRC_LIST) tools/fortran_deps.sh | deps
	@mkdir -p $(OUT)
	@sh tools/fortran_deps.sh $(OBJ_DIR) $(ALL_SRC) > $@

-include $(OUT)/deps.mk

$(OBJ_DIR)/%.o: %.f90 | deps
	@mkdir -p $(OBJ_DIR) $(MOD_DIR)
	$(call step,$(COMPILING),$(FC) $(FFLAGS) -J$(MOD_DIR) -I$(MOD_DIR) -c $< -o $@)

$(BIN_DIR)/flexmech: $(call obj,$(APP_SRC)) $(LIB_OBJ) $(ODEPACK_LIB)
	@mkdir -p $(BIN_DIR)
	$(call step,$(COMPILING),$(FC) $(FFLAGS) -o $@ $^ $(LIBS))
	@echo "built $@"

$(OUT)/tests/%: $(OBJ_DIR)/%.o $(LIB_OBJ) $(TLIB_OBJ) $(ODEPACK_LIB)
	@mkdir -p $(OUT)/tests
	$(call step,$(COMPILING),$(FC) $(FFLAGS) -o $@ $^ $(LIBS))

$(OUT)/tools/%: $(OBJ_DIR)/%.o $(LIB_OBJ) $(ODEPACK_LIB)
	@mkdir -p $(OUT)/tools
	$(call step,$(COMPILING),$(FC) $(FFLAGS) -o $@ $^ $(LIBS))

# Benchmarks may compare with NLopt (optional; installed by `make bench`).
BENCH_LIBS := -lnlopt

# Benchmarks share the tests' fixtures (tests/lib), so they measure the same cases.
$(OUT)/bench/%: $(OBJ_DIR)/%.o $(LIB_OBJ) $(TLIB_OBJ) $(ODEPACK_LIB)
	@mkdir -p $(OUT)/bench
	$(call step,$(COMPILING),$(FC) $(FFLAGS) -o $@ $^ $(BENCH_LIBS) $(LIBS))

test-bins: $(BIN_DIR)/flexmech $(TEST_BIN) $(TOOL_BIN)
	@:

bench-bins: $(BIN_DIR)/flexmech $(BENCH_BIN)

# ---------------------------------------------------------------- user problems
# make PROBLEM=path/to/my_problem.f90: that file (a module `user_problems`,
# template examples/user_problem/hs71_problem.f90) replaces the default
# src/optim/user_problems.f90 in build/user/flexmech; decks name its problems.
# The stamp names the problem file (and the flags): switching to another file,
# even an older one, rebuilds.
ifneq ($(PROBLEM),)
USER_DIR := $(BUILD_DIR)/user
USER_STAMP := $(USER_DIR)/problem.txt
USER_BANNER := flexmech: compiling $(PROBLEM) into $(USER_DIR)
$(shell mkdir -p $(USER_DIR); echo '$(abspath $(PROBLEM)) $(FLAVOUR) $(FFLAGS)' | cmp -s - $(USER_STAMP) || \
  echo '$(abspath $(PROBLEM)) $(FLAVOUR) $(FFLAGS)' > $(USER_STAMP))
all: $(USER_DIR)/flexmech
$(USER_DIR)/flexmech: $(PROBLEM) $(USER_STAMP) $(call obj,$(APP_SRC)) $(filter-out %/user_problems.o,$(LIB_OBJ)) $(ODEPACK_LIB)
	@mkdir -p $(USER_DIR)/mod
	$(call step,$(USER_BANNER),$(FC) $(FFLAGS) -J$(USER_DIR)/mod -I$(MOD_DIR) -c $(PROBLEM) -o $(USER_DIR)/user_problems.o,$(USER_DIR)/build.log)
	$(call step,$(USER_BANNER),$(FC) $(FFLAGS) -o $@ $(USER_DIR)/user_problems.o $(filter %.o %.a,$^) $(LIBS),$(USER_DIR)/build.log)
	@echo "built $@ with the problems of $(PROBLEM)"
endif

# ---------------------------------------------------------------- user targets
run: all
	@mkdir -p $(BUILD_DIR)/out
	@out=$(BUILD_DIR)/out/$(basename $(notdir $(DECK))).out; \
	$(BIN_DIR)/flexmech $(DECK) -o $$out && \
	echo "output written to $$out" && grep -E '^# (summary|cost)' $$out

plot: all
	@test -n "$(PLOT_OUTPUT)" || { echo "usage: make plot OUT=run.out" >&2; exit 1; }
	$(BIN_DIR)/flexmech plot $(PLOT_OUTPUT)

# the paper gallery (doc/gallery.md): the decks of the papers' figures, run and drawn
figures: all
	@sh doc/figures/gallery/gallery.sh $(BIN_DIR)/flexmech $(BUILD_DIR)/gallery

# The flavours build side by side (one sub-make each, sharing the job slots);
# the system packages and ODEPACK come first, once.
test-bins-release test-bins-debug: test-bins-%: deps odepack
	@$(MAKE) --no-print-directory BUILD=$* test-bins
mpi-if-present: deps odepack
	@if command -v mpif90 >/dev/null 2>&1 && command -v mpirun >/dev/null 2>&1; then \
	  $(MAKE) --no-print-directory BUILD=release MPI=1 all; fi

test: test-bins-release test-bins-debug mpi-if-present
	@sh tests/run_tests.sh $(BUILD_DIR)

bench:
	@$(MAKE) --no-print-directory deps EXTRA_PKGS=libnlopt-dev
	@$(MAKE) --no-print-directory BUILD=release bench-bins
	@sh bench/run_bench.sh $(BUILD_DIR)

# Every bench/peers/*.py against the release build (a Python venv with the
# peers' pip packages in build/peers/venv; not part of make test or CI).
PEERS_VENV := $(BUILD_DIR)/peers/venv
bench-peers: all
	@command -v python3 >/dev/null 2>&1 || sh tools/install_deps.sh python3 python3-venv
	@test -x $(PEERS_VENV)/bin/python || python3 -m venv $(PEERS_VENV)
	@$(PEERS_VENV)/bin/python -m pip install -q exudyn==1.13.6 numpy
	@for s in bench/peers/*.py; do \
	  echo "== $$s"; $(PEERS_VENV)/bin/python $$s --flexmech $(BIN_DIR)/flexmech --work $(BUILD_DIR)/peers || exit 1; done

clean:
	rm -rf $(BUILD_DIR)/release $(BUILD_DIR)/debug $(BUILD_DIR)/bin $(BUILD_DIR)/out

# also forgets the ODEPACK download
distclean:
	rm -rf $(BUILD_DIR)

# ---------------------------------------------------------------- inner loop and docs
#   make check        the fast inner loop (a few minutes on 2 cores): every unit suite
#                     (release build) and deck-error test, the decks and scenarios of tests/check.txt
#   make check-docs   the commands of doc/tutorial.md in a scratch directory, the numbers it
#                     quotes, the decks every page names (tests/docs/check_docs.py)
.PHONY: check check-docs

check: test-bins-release test-bins-debug
	@SELECTION=tests/check.txt UNIT_FLAVOUR=release sh tests/run_tests.sh $(BUILD_DIR)

check-docs: all
	@command -v python3 >/dev/null 2>&1 || sh tools/install_deps.sh python3
	@python3 tests/docs/check_docs.py $(BUILD_DIR)

# ---------------------------------------------------------------- reliability
#   make fuzz RUNS=N SEED=S   mutation fuzz of every deck, release and debug builds (FUZZ_JOBS at once)
#   make fuzz-ci              the bounded slice CI runs (fixed seed)
#   make check-debug          every deck of inputs/ and tests/decks/ in the debug build
#   make check-opt            the test suite under -O0, -O2 and -O3 -march=native
#   make check-valgrind       valgrind on one deck of each analysis
RUNS         ?= 300
SEED         ?= 1
FUZZ_TIMEOUT ?= 5
FUZZ_JOBS    ?= $(shell nproc 2>/dev/null || echo 1)
CI_FUZZ_RUNS := 400
OPT_LEVELS   := O0 O2 O3native
OPTFLAGS_O0       := -O0
OPTFLAGS_O2       := -O2
OPTFLAGS_O3native := -O3 -march=native
# one deck of each analysis (a sweep runs its points as child processes of
# the analyses above)
VALGRIND_DECKS := inputs/fourbar_150_damped.nml inputs/tennant_fig4_linear.nml \
                  inputs/opt_hs35_gauss_constrained.nml inputs/lsode_kinetics.nml \
                  inputs/design_bar_frequency.nml inputs/spatial_fourbar_planar_100.nml \
                  inputs/fourbar_150_clearance.nml

.PHONY: fuzz fuzz-ci fuzz-bins check-debug check-opt check-valgrind $(addprefix check-opt-,$(OPT_LEVELS))

fuzz-bins: deps
	@command -v python3 >/dev/null 2>&1 || sh tools/install_deps.sh python3
	@$(MAKE) --no-print-directory BUILD=release all
	@$(MAKE) --no-print-directory BUILD=debug all

fuzz: fuzz-bins
	@nice python3 tests/fuzz/fuzz_decks.py --runs $(RUNS) --seed $(SEED) --timeout $(FUZZ_TIMEOUT) --jobs $(FUZZ_JOBS)

# The design and sweep decks run many analyses and write nothing until they
# end; the fuzzer cannot cap their work yet (it caps transient revolutions),
# so the CI slice leaves them to the full run.
fuzz-ci: fuzz-bins
	@nice python3 tests/fuzz/fuzz_decks.py --runs $(CI_FUZZ_RUNS) --seed 20260101 --timeout $(FUZZ_TIMEOUT) --jobs $(FUZZ_JOBS) \
	  --exclude '/(design|sweep)_'

check-debug: deps
	@$(MAKE) --no-print-directory BUILD=release test-bins
	@$(MAKE) --no-print-directory BUILD=debug test-bins
	@SKIP_UNITS=1 sh tests/run_tests.sh $(BUILD_DIR) '' debug

# Each level builds into its own directory (ODEPACK included, from the same
# sources) and runs the whole suite with unit tests and regression comparisons
# at that level; make check-opt-O3native runs one level.
check-opt: deps odepack
	@fails=""; for l in $(OPT_LEVELS); do \
	  $(MAKE) --no-print-directory check-opt-$$l || fails="$$fails $$l"; done; \
	  if [ -n "$$fails" ]; then echo "check-opt: failures at:$$fails"; exit 1; fi; \
	  echo "check-opt: the suite passes at $(OPT_LEVELS)"

$(addprefix check-opt-,$(OPT_LEVELS)): check-opt-%: deps odepack
	@echo "== optimization level $* ($(OPTFLAGS_$*))"
	@nice $(MAKE) --no-print-directory BUILD=release BUILD_DIR=$(BUILD_DIR)/opt/$* \
	  ODEPACK_SRC=$(abspath $(ODEPACK_SRC)) FFLAGS_release='$(OPTFLAGS_$*) -g $(WARN)' test-bins
	@UNIT_FLAVOUR=release sh tests/run_tests.sh $(BUILD_DIR)/opt/$* '' release

# valgrind's memcheck on one deck of each analysis (release build, -O2 -g):
# any invalid access or use of an uninitialised value fails.
check-valgrind: all
	@command -v valgrind >/dev/null 2>&1 || sh tools/install_deps.sh valgrind
	@mkdir -p $(BUILD_DIR)/valgrind; fails=0; \
	for d in $(VALGRIND_DECKS); do \
	  n=$$(basename $$d .nml); \
	  if nice valgrind -q --error-exitcode=99 --track-origins=yes $(BIN_DIR)/flexmech $$d \
	       -o $(BUILD_DIR)/valgrind/$$n.out > $(BUILD_DIR)/valgrind/$$n.log 2>&1; then \
	    echo "   $$n: no valgrind errors"; \
	  else echo "   $$n: FAILED (see $(BUILD_DIR)/valgrind/$$n.log)"; fails=$$((fails + 1)); fi; \
	done; [ $$fails -eq 0 ]
