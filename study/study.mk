# study.mk - bin/study, the campaign driver, and the unit tests of its modules
# (included by the top-level Makefile after lib/lib.mk). It links the floor (lib/: the
# runs directory's layout and locks, the result columns, the run-file reader, the flux
# through a band an [onset] search classifies its runs by, the statistics) and the
# engine library for the one parameter table (params_set, params_hash, ...); never
# analysis/ (tests/integration/floors.sh).
# study_main.c and the sub-folders (study/README.md, "Source tour"); each folder's
# files include the others' as "folder/name.h" (-Istudy), lib/ and core/ by name
STUDY_SRC = $(wildcard study/*.c study/*/*.c)
STUDY_OBJ = $(STUDY_SRC:%.c=$(BUILD)/%.o)
STUDY     = $(BIN)/study
# every module but the driver's main: what the unit tests link against
STUDY_MOD = $(filter-out $(BUILD)/study/study_main.o,$(STUDY_OBJ))
STUDY_TSRC = $(wildcard tests/unit/study_*.c)
STUDY_TBIN = $(STUDY_TSRC:%.c=$(BUILD)/%)

$(BUILD)/study/%.o: ALLCFLAGS += -Istudy -Ilib

$(STUDY): $(STUDY_OBJ) $(FLOOR) $(LIB)
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  LD    $@")
	$(Q)$(CC) $(LDFLAGS) -o $@ $(STUDY_OBJ) $(FLOOR) $(LIB) $(PKG_LIBS)

# more specific than the top-level tests rule: links the study modules too
$(BUILD)/tests/unit/study_%: tests/unit/study_%.c $(STUDY_MOD) $(FLOOR) $(LIB) tests/testlib.h $(BUILD)/flags
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) $(ALLCFLAGS) -Itests -Istudy -Ilib $(LDFLAGS) -o $@ $< $(STUDY_MOD) $(FLOOR) $(LIB) $(PKG_LIBS)

all: $(STUDY)
tests: $(STUDY) $(STUDY_TBIN)
