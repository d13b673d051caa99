# study.mk - bin/study, the campaign driver, and the unit tests of its modules
# (included by the top-level Makefile). It links the engine library for the one
# parameter table (params_set, params_hash, ...), and the analysis library for the one
# definition of a run's flux through a band (analysis/flux.c), which an [onset]
# search classifies its runs by.
STUDY_SRC = $(wildcard study/*.c)
STUDY_OBJ = $(STUDY_SRC:%.c=$(BUILD)/%.o)
STUDY     = $(BIN)/study
# every module but the driver's main: what the unit tests link against
STUDY_MOD = $(filter-out $(BUILD)/study/study_main.o,$(STUDY_OBJ))
STUDY_TSRC = $(wildcard tests/unit/study_*.c)
STUDY_TBIN = $(STUDY_TSRC:%.c=$(BUILD)/%)
# analysis.mk's AN_LIB (that file is included after this one)
STUDY_AN   = $(BUILD)/analysis/libanalysis.a

$(BUILD)/study/%.o: ALLCFLAGS += -Istudy -Ianalysis

$(STUDY): $(STUDY_OBJ) $(STUDY_AN) $(LIB)
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  LD    $@")
	$(Q)$(CC) $(LDFLAGS) -o $@ $(STUDY_OBJ) $(STUDY_AN) $(LIB) $(PKG_LIBS)

# more specific than the top-level tests rule: links the study modules too
$(BUILD)/tests/unit/study_%: tests/unit/study_%.c $(STUDY_MOD) $(STUDY_AN) $(LIB) tests/testlib.h $(BUILD)/flags
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) $(ALLCFLAGS) -Itests -Istudy -Ianalysis $(LDFLAGS) -o $@ $< $(STUDY_MOD) $(STUDY_AN) $(LIB) $(PKG_LIBS)

all: $(STUDY)
tests: $(STUDY) $(STUDY_TBIN)
