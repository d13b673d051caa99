# study.mk - bin/study, the campaign driver (included by the top-level Makefile).
# It links the engine library for the one parameter table (params_set, params_hash, ...).
STUDY_SRC = $(wildcard study/*.c)
STUDY_OBJ = $(STUDY_SRC:%.c=$(BUILD)/%.o)
STUDY     = $(BIN)/study

$(BUILD)/study/%.o: ALLCFLAGS += -Istudy

$(STUDY): $(STUDY_OBJ) $(LIB)
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  LD    $@")
	$(Q)$(CC) $(LDFLAGS) -o $@ $(STUDY_OBJ) $(LIB) $(PKG_LIBS)

all: $(STUDY)
tests: $(STUDY)
