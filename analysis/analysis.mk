# analysis.mk - the analysis tools, bin/NAME for each NAME of AN_MAIN, and their tests
# (included by the top-level Makefile after lib/lib.mk). The modules (common/: the
# frame every tool shares; measure/: what the tools compute) go into
# $(BUILD)/analysis/libanalysis.a; each tool is one tools/NAME_main.c.
# AN_MAIN is the one list of the tools: scripts, tests and docs read it (`make
# print-tools`, `make print-campaign-tools`) or are checked against it
# (scripts/docs_lists.sh). AN_CAMPAIGN: the tools that read a campaign's runs (TOOL
# CAMPAIGN --runs DIR); bin/dumpflux reads one run file or another code's dump.
AN_MAIN   = onset hysteresis waiting figures dumpflux rolls ring whale convect movie
AN_CAMPAIGN = $(filter-out dumpflux movie,$(AN_MAIN))
AN_SRC    = $(wildcard analysis/common/*.c analysis/measure/*.c)
AN_OBJ    = $(AN_SRC:%.c=$(BUILD)/%.o)
AN_LIB    = $(BUILD)/analysis/libanalysis.a
AN_BIN    = $(AN_MAIN:%=$(BIN)/%)
AN_TSRC   = $(wildcard tests/analysis/*.c)
AN_TBIN   = $(AN_TSRC:%.c=$(BUILD)/%)

$(BUILD)/analysis/%.o: ALLCFLAGS += -Ianalysis -Ilib

# made afresh (as libshake.a): a module moved elsewhere must not stay in the archive
$(AN_LIB): $(AN_OBJ)
	@$(if $(filter 0,$(V)),echo "  AR    $@")
	$(Q)rm -f $@ && ar rcs $@ $^

$(AN_BIN): $(BIN)/%: $(BUILD)/analysis/tools/%_main.o $(AN_LIB) $(FLOOR) $(LIB)
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  LD    $@")
	$(Q)$(CC) $(LDFLAGS) -o $@ $< $(AN_LIB) $(FLOOR) $(LIB) $(PKG_LIBS)

# the fault tests' links with the shared HDF5 (the Makefile's H5SHARED says why)
$(AN_MAIN:%=$(H5SHARED)/%): $(H5SHARED)/%: $(BUILD)/analysis/tools/%_main.o $(AN_LIB) $(FLOOR) $(LIB)
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  LD    $@")
	$(Q)$(CC) $(LDFLAGS) -o $@ $< $(AN_LIB) $(FLOOR) $(LIB) $(PKG_LIBS_SHARED)

# more specific than the top-level tests rule: links the analysis modules too
$(BUILD)/tests/analysis/%: tests/analysis/%.c $(AN_LIB) $(FLOOR) $(LIB) tests/testlib.h $(BUILD)/flags
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) $(ALLCFLAGS) -Itests -Ianalysis -Ilib $(LDFLAGS) -o $@ $< $(AN_LIB) $(FLOOR) $(LIB) $(PKG_LIBS)

all: $(AN_BIN)
tests: $(AN_BIN) $(AN_TBIN) $(H5SHARED)/waiting $(H5SHARED)/whale

# make figures: the figures of analysis/README.md (PNG and PDF in analysis/figures/, with
# the tables the tools printed, NAME.txt) from the campaigns in campaigns/figures/, so that a
# committed figure is what today's tools draw from today's engine. Each campaign runs
# in its own runs directory under build/figures/, again from scratch when its file or
# the engine's sources change (not when bin/shake is only relinked: its version stamp
# changes with every commit); a campaign interrupted before it was done is resumed.
# The tools run again whenever they are rebuilt.
FIG_DIR    = analysis/figures
FIG_RUNS   = build/figures
FIG_CAMP   = campaigns/figures
FIG_JOBS  ?= 2
FIG_ENGINE = $(wildcard core/*/*.c core/*/*.h)
FIG_PNGS   = $(FIG_DIR)/onset.png $(FIG_DIR)/hysteresis.png $(FIG_DIR)/waiting_km.png $(FIG_DIR)/fig1.png

.PHONY: figures
figures: $(FIG_PNGS)

$(FIG_RUNS)/%/done: $(FIG_CAMP)/%.campaign $(FIG_ENGINE) | $(SHAKE) $(STUDY)
	$(Q)if [ -e $@ ]; then rm -rf $(FIG_RUNS)/$*; fi
	@echo "  RUN   $<"
	$(Q)$(STUDY) run $< --runs $(FIG_RUNS)/$* --jobs $(FIG_JOBS) --no-progress
	$(Q)touch $@

# fig_tool OUT-NAME, TOOL, CAMPAIGN, OPTIONS, FIGURES: the tool's table into
# FIG_DIR/OUT-NAME.txt, its figures (PNG and PDF) copied beside it
define fig_tool
	@echo "  FIG   $(FIG_DIR)/$(1)"
	$(Q)$(BIN)/$(2) $(3) --runs $(FIG_RUNS)/$(3) --out $(FIG_RUNS)/$(3)/analysis $(4) >$(FIG_DIR)/$(1).txt
	$(Q)for n in $(5); do cp $(FIG_RUNS)/$(3)/analysis/$$n.png $(FIG_RUNS)/$(3)/analysis/$$n.pdf $(FIG_DIR)/; done
endef

$(FIG_DIR)/onset.png: $(FIG_RUNS)/readme/done $(BIN)/onset
	$(call fig_tool,onset,onset,readme,,onset)
$(FIG_DIR)/fig1.png: $(FIG_RUNS)/readme/done $(BIN)/figures
	$(call fig_tool,figures,figures,readme,--freq 4.5$(,)5$(,)5.5,fig1 fig3)
$(FIG_DIR)/hysteresis.png: $(FIG_RUNS)/hyst/done $(BIN)/hysteresis
	$(call fig_tool,hysteresis,hysteresis,hyst,,hysteresis)
$(FIG_DIR)/waiting_km.png: $(FIG_RUNS)/wait/done $(BIN)/waiting
	$(call fig_tool,waiting,waiting,wait,,waiting_km waiting_hist)
, := ,
