#!/usr/bin/env bash
# one_place_core.sh - facts core/ claims to hold in one place, held there: a second
# copy fails here (a source-only check, no build). The drive's axes are rows of one
# table (core/model/drive.c): no other file of core/, lib/, study/ or analysis/ spells an axis's
# name, words or symbol, or tells the axes apart by hand. The scene's keys are made by
# one mechanism, a hand row of params.c's table each with its field in sb_scene of the
# same name, and SB_NKEYS (params.h, the size of the per-key arrays) is their number.
# Only core/run/shake_main.c prints (docs/engine.md): no other file of core/ writes to
# stdout or stderr (a library writes to the FILE * it is given, and reports progress
# through the caller's function, core/run/sim.h). A check of the checker first: a
# made-up second copy of each must fail.
cd "$(dirname "$0")/../.."
source tests/integration/lib.sh

# axes DIR...: the lines that spell a drive axis out outside its table: the axis names
# and words as string literals, the symbols, a kind compared by hand (== AXIS_GAMMA,
# case AXIS_VELOCITY). core/run/h5out.c's "velocity" is the H5MD element of the disks'
# velocities, another fact.
axes() {
	grep -rnE --include='*.c' --include='*.h' \
		'"(gamma|Gamma|velocity|peak acceleration|peak velocity|Γ)"|(==|!=|case) *AXIS_(GAMMA|VELOCITY)|AXIS_(GAMMA|VELOCITY) *(==|!=|\?)' "$@" |
		grep -v '^core/model/drive\.[ch]:' | grep -vE '^core/run/h5out\.c:[0-9]+:.*(h5w_elem_create|"position", "velocity")' |
		grep -vE '^lib/schema\.c:[0-9]+:static const char \*const VIEW_AXES' # the runs view's column names of the axes
}
# keys PARAMS_H PARAMS_C: the scene's fields (struct sb_scene, without the per-key
# arrays src and by_preset) and the table's hand rows ({"key", TYPE(key), ...}), one
# "field NAME" / "row NAME" a line, then "nkeys N" (SB_NKEYS)
keys() {
	awk '/^struct sb_scene \{/ { on = 1; next } on && /^\};/ { on = 0 }
		on { sub(/\/\*.*/, ""); sub(/^[ \t]+/, "")
		     if ($0 ~ /^(int|long|double|char|unsigned char) /) { sub(/^(unsigned char|int|long|double|char) /, ""); sub(/;.*/, "")
			n = split($0, v, ","); for (i = 1; i <= n; i++) { f = v[i]; gsub(/[ \t]|\[.*/, "", f); if (f != "src" && f != "by_preset") print "field", f } }
		     else if ($0 != "" && $0 !~ /^\*/) print "other", $0 }
		/^#define SB_NKEYS / { print "nkeys", $3 }' "$1"
	sed -n 's/^[ \t]*{"\([a-z_0-9]*\)", \(INT\|REAL\|BOOL\|ENUM\|STR\)(\([a-z_0-9]*\)).*/row \1 \3/p' "$2"
}
# keys_bad < KEYS: what is not one field, one row of the same name, SB_NKEYS of them
keys_bad() {
	awk '$1 == "field" { f[$2]++; nf++ } $1 == "row" { r[$2]++; nr++; if ($2 != $3) print "row " $2 " writes field " $3 }
		$1 == "other" { print "a field not declared as one of the scene'"'"'s C types: " $0 }
		$1 == "nkeys" { nk = $2 }
		END { for (k in f) if (f[k] != 1 || r[k] != 1) print "field " k ": " f[k] + 0 " fields, " r[k] + 0 " rows"
		      for (k in r) if (!(k in f)) print "row " k " without a field"
		      if (nr != nk || nf != nk) print "SB_NKEYS is " nk ", with " nf " fields and " nr " rows" }'
}

# prints DIR...: the lines of core/ outside shake_main.c that print on their own
prints() {
	grep -rnE --include='*.c' --include='*.h' '\( *(stdout|stderr)\b|, *(stdout|stderr) *\)|(^|[^a-z_])(printf|puts|perror|putchar)\(' "$@" |
		grep -v '^core/run/shake_main\.c:'
}

# the checker, on made-up copies
mkdir -p "$TMP/x"
printf 'static const char *w = "peak velocity";\nint k = kind == AXIS_GAMMA ? 2 : 1;\n' >"$TMP/x/copy.c"
n=$(axes "$TMP/x" | wc -l)
check one_place_core.selftest.axes "a made-up second copy of the axes was not found twice ($n)" test "$n" = 2
sed 's/^\tlong bed_kinetic_samples, bed_height_samples;/\tREC_KEYS(SB_SCENE_FIELD_)/' core/scene/params.h >"$TMP/params.h"
check one_place_core.selftest.copy "the made-up params.h is the same as the real one" test -n "$(cmp "$TMP/params.h" core/scene/params.h 2>&1)"
bad=$(keys "$TMP/params.h" core/scene/params.c | keys_bad)
check one_place_core.selftest.keys "fields made by a second mechanism were not found" test -n "$bad"
nk=$(sed -n 's/^#define SB_NKEYS \([0-9]*\).*/\1/p' core/scene/params.h)
sed "s/^#define SB_NKEYS [0-9]*/#define SB_NKEYS $((nk + 1))/" core/scene/params.h >"$TMP/params.h"
bad=$(keys "$TMP/params.h" core/scene/params.c | keys_bad)
check one_place_core.selftest.nkeys "an SB_NKEYS above the number of keys was not found" test -n "$bad"

printf '\tfprintf(stderr, "x");\n\tprintf("y");\n\tfputc(10, stdout);\n\tfprintf(f, "z");\n\tsnprintf(b, n, "w on stderr");\n' >"$TMP/x/print.c"
n=$(prints "$TMP/x" | wc -l)
check one_place_core.selftest.prints "the three made-up prints were not found alone ($n)" test "$n" = 3

bad=$(prints core)
if [ -z "$bad" ]; then ok one_place_core.only_main_prints; else fail one_place_core.only_main_prints "core/ prints outside shake_main.c:
$bad"; fi
bad=$(axes core lib study analysis)
if [ -z "$bad" ]; then ok one_place_core.axes; else fail one_place_core.axes "the drive's axes spelled out outside core/model/drive.c:
$bad"; fi
bad=$(keys core/scene/params.h core/scene/params.c | keys_bad)
n=$(keys core/scene/params.h core/scene/params.c | grep -c '^row ')
check one_place_core.keys.some "only $n rows of params.c's table were read" test "$n" -ge 70
if [ -z "$bad" ]; then ok one_place_core.keys; else fail one_place_core.keys "$bad"; fi
finish
