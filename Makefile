# flexmech: nonlinear analysis and optimal design of flexible mechanisms.
#
#   make run     build and run the default deck (prints where the output went)
#   make test    build (release and debug), run unit, deck-error and regression tests
#   make bench   work-precision and cost studies (figures, not pass/fail)
#   make deps    install missing system packages and fetch ODEPACK (done by every target)
#
# Our own code builds with -std=f2008 -Wall -Wextra, warning-free.  ODEPACK is
# compiled from Debian's octave source package with its own legacy flags.

FC        ?= gfortran
ifeq ($(origin FC),default)
FC        := gfortran
endif
BUILD     ?= release
BUILD_DIR := build
ODEPACK_SRC ?= $(BUILD_DIR)/odepack/src
DECK      ?= inputs/fourbar_150_damped.nml
LIBS      := -llapack -lblas

WARN      := -std=f2008 -Wall -Wextra -Wimplicit-interface -fimplicit-none
FFLAGS_release := -O2 -g $(WARN)
FFLAGS_debug   := -O0 -g $(WARN) -fcheck=all -ffpe-trap=invalid,zero,overflow -fbacktrace
LEGACY_FFLAGS  := -O2 -g -std=legacy -w

FFLAGS    := $(FFLAGS_$(BUILD))
OUT       := $(BUILD_DIR)/$(BUILD)
OBJ_DIR   := $(OUT)/obj
MOD_DIR   := $(OUT)/mod
BIN_DIR   := $(if $(filter release,$(BUILD)),$(BUILD_DIR)/bin,$(OUT)/bin)

LIB_SRC   := $(sort $(shell find src -name '*.f90' ! -path 'src/app/*'))
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

ODEPACK_FILES := dlsode dstode dprepj dsolsy dintdy dcfode dewset dvnorm
ODEPACK_LIB   := $(BUILD_DIR)/odepack/libodepack.a

vpath %.f90 $(sort $(dir $(ALL_SRC)))

.PHONY: all deps odepack run test test-bins bench clean distclean help
.DEFAULT_GOAL := all

all: $(BIN_DIR)/flexmech

help:
	@sed -n '3,9p' Makefile

# ---------------------------------------------------------------- dependencies
deps:
	@sh tools/install_deps.sh $(EXTRA_PKGS)

$(ODEPACK_SRC)/dlsode.f: | deps
	@sh tools/fetch_odepack.sh $(BUILD_DIR) $(ODEPACK_SRC)

odepack: $(ODEPACK_LIB)

$(ODEPACK_LIB): $(ODEPACK_SRC)/dlsode.f
	@mkdir -p $(BUILD_DIR)/odepack/obj
	@for f in $(ODEPACK_FILES); do \
	  $(FC) $(LEGACY_FFLAGS) -c $(ODEPACK_SRC)/$$f.f -o $(BUILD_DIR)/odepack/obj/$$f.o || exit 1; done
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
	$(FC) $(FFLAGS) -J$(MOD_DIR) -I$(MOD_DIR) -c $< -o $@

$(BIN_DIR)/flexmech: $(call obj,$(APP_SRC)) $(LIB_OBJ) $(ODEPACK_LIB)
	@mkdir -p $(BIN_DIR)
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

$(OUT)/tests/%: $(OBJ_DIR)/%.o $(LIB_OBJ) $(TLIB_OBJ) $(ODEPACK_LIB)
	@mkdir -p $(OUT)/tests
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

$(OUT)/tools/%: $(OBJ_DIR)/%.o $(LIB_OBJ) $(ODEPACK_LIB)
	@mkdir -p $(OUT)/tools
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

# Benchmarks may compare with NLopt (optional; installed by `make bench`).
BENCH_LIBS := -lnlopt

# Benchmarks share the tests' fixtures (tests/lib), so they measure the same cases.
$(OUT)/bench/%: $(OBJ_DIR)/%.o $(LIB_OBJ) $(TLIB_OBJ) $(ODEPACK_LIB)
	@mkdir -p $(OUT)/bench
	$(FC) $(FFLAGS) -o $@ $^ $(BENCH_LIBS) $(LIBS)

test-bins: $(BIN_DIR)/flexmech $(TEST_BIN) $(TOOL_BIN)

bench-bins: $(BIN_DIR)/flexmech $(BENCH_BIN)

# ---------------------------------------------------------------- user problems
# make PROBLEM=path/to/my_problem.f90: that file (a module `user_problems`,
# template examples/user_problem/hs71_problem.f90) replaces the default
# src/optim/user_problems.f90 in build/user/flexmech; decks name its problems.
ifneq ($(PROBLEM),)
USER_DIR := $(BUILD_DIR)/user
all: $(USER_DIR)/flexmech
$(USER_DIR)/flexmech: $(PROBLEM) $(call obj,$(APP_SRC)) $(filter-out %/user_problems.o,$(LIB_OBJ)) $(ODEPACK_LIB)
	@mkdir -p $(USER_DIR)/mod
	$(FC) $(FFLAGS) -J$(USER_DIR)/mod -I$(MOD_DIR) -c $(PROBLEM) -o $(USER_DIR)/user_problems.o
	$(FC) $(FFLAGS) -o $@ $(USER_DIR)/user_problems.o $(filter %.o %.a,$^) $(LIBS)
	@echo "built $@ with the problems of $(PROBLEM)"
endif

# ---------------------------------------------------------------- user targets
run: all
	@mkdir -p $(BUILD_DIR)/out
	@out=$(BUILD_DIR)/out/$(basename $(notdir $(DECK))).out; \
	$(BIN_DIR)/flexmech $(DECK) -o $$out && \
	echo "output written to $$out" && grep -E '^# (summary|cost)' $$out

test: deps
	@$(MAKE) --no-print-directory BUILD=release test-bins
	@$(MAKE) --no-print-directory BUILD=debug test-bins
	@sh tests/run_tests.sh $(BUILD_DIR)

bench:
	@$(MAKE) --no-print-directory deps EXTRA_PKGS=libnlopt-dev
	@$(MAKE) --no-print-directory BUILD=release bench-bins
	@sh bench/run_bench.sh $(BUILD_DIR)

clean:
	rm -rf $(BUILD_DIR)/release $(BUILD_DIR)/debug $(BUILD_DIR)/bin $(BUILD_DIR)/out

# also forgets the ODEPACK download
distclean:
	rm -rf $(BUILD_DIR)
