# study.mk - bin/study, the campaign driver, and the unit tests of its modules
# (included by the top-level Makefile). It links the engine library for the one
# parameter table (params_set, params_hash, ...).
STUDY_SRC = $(wildcard study/*.c)
STUDY_OBJ = $(STUDY_SRC:%.c=$(BUILD)/%.o)
STUDY     = $(BIN)/study
# every module but the driver's main: what the unit tests link against
STUDY_MOD = $(filter-out $(BUILD)/study/study_main.o,$(STUDY_OBJ))
STUDY_TSRC = $(wildcard tests/unit/study_*.c)
STUDY_TBIN = $(STUDY_TSRC:%.c=$(BUILD)/%)

$(BUILD)/study/%.o: ALLCFLAGS += -Istudy

$(STUDY): $(STUDY_OBJ) $(LIB)
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  LD    $@")
	$(Q)$(CC) $(LDFLAGS) -o $@ $(STUDY_OBJ) $(LIB) $(PKG_LIBS)

# more specific than the top-level tests rule: links the study modules too
$(BUILD)/tests/unit/study_%: tests/unit/study_%.c $(STUDY_MOD) $(LIB) tests/testlib.h $(BUILD)/flags
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) $(ALLCFLAGS) -Itests -Istudy $(LDFLAGS) -o $@ $< $(STUDY_MOD) $(LIB) $(PKG_LIBS)

all: $(STUDY)
tests: $(STUDY) $(STUDY_TBIN)
