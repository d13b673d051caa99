# lib.mk - the floor study/ and analysis/ both stand on (included by the top-level
# Makefile before them): $(BUILD)/lib/libfloor.a, built from lib/*.c against the engine
# (core/) only. What it holds is listed in lib/README.md; tests/integration/floors.sh
# fails when a module here calls up into study/ or analysis/.
FLOOR_SRC = $(wildcard lib/*.c)
FLOOR_OBJ = $(FLOOR_SRC:%.c=$(BUILD)/%.o)
FLOOR     = $(BUILD)/lib/libfloor.a

$(BUILD)/lib/%.o: ALLCFLAGS += -Ilib

# made afresh (as libshake.a): a module moved elsewhere must not stay in the archive
$(FLOOR): $(FLOOR_OBJ)
	@$(if $(filter 0,$(V)),echo "  AR    $@")
	$(Q)rm -f $@ && ar rcs $@ $^
