# analysis.mk - the analysis tools bin/onset, bin/hysteresis, bin/waiting, bin/figures
# and their tests (included by the top-level Makefile). Shared modules go into
# $(BUILD)/analysis/libanalysis.a; each tool is one *_main.c.
AN_MAIN   = onset hysteresis waiting figures
AN_SRC    = $(filter-out %_main.c,$(wildcard analysis/*.c))
# and study/layout.o: the runs directory's layout is bin/study's
AN_OBJ    = $(AN_SRC:%.c=$(BUILD)/%.o) $(BUILD)/study/layout.o
AN_LIB    = $(BUILD)/analysis/libanalysis.a
AN_BIN    = $(AN_MAIN:%=$(BIN)/%)
AN_TSRC   = $(wildcard tests/analysis/*.c)
AN_TBIN   = $(AN_TSRC:%.c=$(BUILD)/%)

$(BUILD)/analysis/%.o: ALLCFLAGS += -Ianalysis -Istudy

$(AN_LIB): $(AN_OBJ)
	@$(if $(filter 0,$(V)),echo "  AR    $@")
	$(Q)ar rcs $@ $^

$(AN_BIN): $(BIN)/%: $(BUILD)/analysis/%_main.o $(AN_LIB) $(LIB)
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  LD    $@")
	$(Q)$(CC) $(LDFLAGS) -o $@ $< $(AN_LIB) $(LIB) $(PKG_LIBS)

# more specific than the top-level tests rule: links the analysis modules too
$(BUILD)/tests/analysis/%: tests/analysis/%.c $(AN_LIB) $(LIB) tests/testlib.h $(BUILD)/flags
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) $(ALLCFLAGS) -Itests -Ianalysis $(LDFLAGS) -o $@ $< $(AN_LIB) $(LIB) $(PKG_LIBS)

all: $(AN_BIN)
tests: $(AN_BIN) $(AN_TBIN)
