#!/usr/bin/env bash
# version.sh CC FLAGS [MARCH] - the provenance compiled into bin/shake (git hash, dirty
# flag, compiler and flags, the MARCH the build was made for: empty for every CPU).
# Prints a C header.
cc="$1"; flags="$2"; march="${3:-}"
hash=$(git rev-parse --verify -q HEAD 2>/dev/null || echo unknown)
dirty=0
if git rev-parse --verify -q HEAD >/dev/null 2>&1; then
	git diff --quiet HEAD -- 2>/dev/null || dirty=1
fi
ccv=$($cc --version 2>/dev/null | head -n1)
esc() { printf '%s' "$1" | sed 's/\\/\\\\/g; s/"/\\"/g'; }
echo "#define SB_GIT_HASH \"$(esc "$hash")\""
echo "#define SB_GIT_DIRTY $dirty"
echo "#define SB_COMPILER \"$(esc "$ccv")\""
echo "#define SB_CFLAGS \"$(esc "$flags")\""
echo "#define SB_MARCH \"$(esc "$march")\""
