#!/usr/bin/env bash
# floors.sh - the code's floors hold: every call between object files (read with nm
# from the build the suite tests) points down the order core < lib < {study, analysis},
# never between study/ and analysis/, and no two sub-folders of a room, and no two
# files, call each other in a circle (lib/README.md); in lib/ and study/ every object's
# exported functions carry one module prefix (ingest_run, ingest_on_done, ...), and a
# header that says it is private to a folder is included from that folder only. Inside
# core/ the same for its rooms (core/README.md): every file in one of the rooms the
# Makefile names (CORE_ROOMS, lowest first), no file including a header of a room above
# its own, no circle of rooms or files; and the upper rooms include only core's public
# headers (core/README.md, "The public face"). A check of the checker first: a made-up
# upward call, a made-up circle, a made-up second prefix, a made-up include of a private
# header, a file in no room, an upward include and a private core header included from
# above must fail.
cd "$(dirname "$0")/../.."
source tests/integration/lib.sh

# The objects of the build SHAKE belongs to (build/san/bin/shake: build/san; bin/shake:
# build/rel).
case "$SHAKE" in
*/build/*/bin/shake) BUILD=${SHAKE%/bin/shake} ;;
*) BUILD=$REPO/build/rel ;;
esac

# edges BUILD: "FROM TO SYMBOL" for every global symbol an object uses and another
# defines (FROM, TO: source paths without .c, e.g. study/local/driver); objects whose
# source is gone (moved or deleted since that build) are left out
edges() {
	local objs
	objs=$(cd "$1" && find core lib study analysis -name '*.o' 2>/dev/null | sort |
		while read -r o; do [ -f "$REPO/${o%.o}.c" ] && echo "$o"; done)
	[ -n "$objs" ] || return 0
	# nm -A: "OBJ.o:VALUE TYPE SYMBOL" (defined), "OBJ.o:   U SYMBOL" (used)
	(cd "$1" && nm -A -g --defined-only $objs && nm -A -u $objs) | awk '
		{ o = $1; sub(/\.o:.*/, "", o) }
		$(NF - 1) == "U" { use[++n] = o " " $NF; next }
		$(NF - 1) ~ /^[TDBRCV]$/ { def[$NF] = o }
		END { for (i = 1; i <= n; i++) { split(use[i], u, " "); if (u[2] in def && def[u[2]] != u[1]) print u[1], def[u[2]], u[2] } }'
}

# rooms < EDGES: the calls that point up or sideways, one per line
rooms() {
	awk 'function rank(r) { return r == "core" ? 0 : r == "lib" ? 1 : 2 }
		{ split($1, a, "/"); split($2, b, "/")
		  if (a[1] != b[1] && (rank(b[1]) > rank(a[1]) || rank(b[1]) == rank(a[1])))
			print $1 " -> " $2 " (" $3 "): " a[1] "/ may not call " b[1] "/" }'
}

# loops LEVEL < EDGES: the members of the circles among sub-folders (LEVEL folders) or
# files (LEVEL files) of core/, study/ and analysis/, as tsort finds them, on one line
loops() {
	awk -v level="$1" '
		function node(p,   n, a) { n = split(p, a, "/"); return level == "files" ? p : n > 2 ? a[1] "/" a[2] : a[1] "/" }
		$1 ~ /^(core|study|analysis)\// { f = node($1); t = node($2); if (f != t) print f, t }' | sort -u |
		tsort 2>&1 >/dev/null | sed -n 's/^tsort: //p' | grep -v 'input contains a loop' | sort -u | tr '\n' ' '
}

# The checker, on made-up calls: a lib/ module calling study/, analysis/ calling
# study/, and two study/ folders calling each other must each be found.
up=$(printf 'lib/layout study/local/driver driver_run\n' | rooms)
check floors.selftest.upward "a lib -> study call was not reported" test -n "$up"
side=$(printf 'analysis/common/cli study/ledger/db db_open\n' | rooms)
check floors.selftest.sideways "an analysis -> study call was not reported" test -n "$side"
circ=$(printf 'study/a/x study/b/y y\nstudy/b/y study/a/x x\n' | loops folders)
check floors.selftest.circle "a circle of two folders was not reported" test -n "$circ"
down=$(printf 'study/a/x lib/layout layout_db\nlib/layout core/base/err sb_errf\n' | rooms)
check floors.selftest.down "a downward call was reported: $down" test -z "$down"

# core's rooms, lowest first, as the Makefile builds them
CORE_ROOMS=$(sed -n 's/^CORE_ROOMS *= *//p' Makefile)
# roomless ROOMS < PATHS: the files of core/ that are in none of the rooms (README.md,
# the tour, stands in core/ itself)
roomless() {
	awk -v rooms="$1" 'BEGIN { n = split(rooms, r, " "); for (i = 1; i <= n; i++) room[r[i]] = 1 }
		$0 == "core/README.md" { next }
		{ k = split($0, a, "/"); if (k != 3 || !(a[2] in room)) print }'
}
# includes DIR...: "FILE HEADER" for every quoted #include of the sources under DIR
includes() {
	grep -rHo --include='*.c' --include='*.h' '^#include "[^"]*"' "$@" 2>/dev/null | sed 's/:#include "/ /; s/"$//'
}
# core_up ROOMS HEADERS < INCLUDES: the includes by a core file of a header of a room
# above its own (HEADERS: core's headers as core/ROOM/NAME.h; a name not among them,
# as the build's version.h, is no core header)
core_up() {
	awk -v rooms="$1" -v heads="$2" '
		BEGIN { n = split(rooms, r, " "); for (i = 1; i <= n; i++) rank[r[i]] = i
			m = split(heads, h, " "); for (i = 1; i <= m; i++) { split(h[i], p, "/"); room[p[3]] = p[2] } }
		$1 ~ /^core\// { split($1, a, "/"); t = room[$2]
			if (t != "" && rank[t] > rank[a[2]]) print $1 " includes " $2 ": " a[2] "/ may not include " t "/" }'
}
# private PUBLIC HEADERS < INCLUDES: the includes from outside core/ of a core header
# that is not among the public ones (PUBLIC: ROOM/NAME.h)
private() {
	awk -v pub="$1" -v heads="$2" '
		BEGIN { n = split(pub, p, " "); for (i = 1; i <= n; i++) { split(p[i], q, "/"); ok[q[2]] = 1 }
			m = split(heads, h, " "); for (i = 1; i <= m; i++) { split(h[i], q, "/"); room[q[3]] = q[2] } }
		$1 !~ /^core\// && ($2 in room) && !($2 in ok) { print $1 " includes " room[$2] "/" $2 ", which is not public" }'
}
lost=$(printf 'core/base/err.c\ncore/err.c\ncore/attic/x.c\ncore/README.md\n' | roomless "base run")
check floors.selftest.core_roomless "files in no room were not both reported: $lost" test "$(echo "$lost" | wc -l)" = 2
up=$(printf 'core/base/err.c sim.h\ncore/run/sim.c err.h\n' | core_up "base run" "core/base/err.h core/run/sim.h")
check floors.selftest.core_up "the include of run/ by base/ was not reported alone: $up" test "$(echo "$up" | grep -c 'base/ may not include run/')" = 1 -a "$(echo "$up" | wc -l)" = 1
priv=$(printf 'lib/x.c sim.h\nlib/x.c err.h\nlib/x.c lib.h\n' | private "base/err.h" "core/base/err.h core/run/sim.h")
check floors.selftest.core_private "the private header alone was not reported: $priv" test "$(echo "$priv" | grep -c 'run/sim.h')" = 1 -a "$(echo "$priv" | wc -l)" = 1

# prefixes < "OBJECT SYMBOL" lines: the objects whose exported functions begin with
# more than one prefix (the name up to its first '_'), with the prefixes
prefixes() {
	awk '{ p = $2; sub(/_.*/, "", p); if (!((p, $1) in seen)) { seen[p, $1] = 1; n[$1]++; l[$1] = l[$1] " " p } }
		END { for (o in n) if (n[o] > 1) print o ":" l[o] }' | sort
}
# private_includes DIR: "FILE includes HEADER, private to FOLDER/" for every include of
# a header under DIR whose first line says "private to FOLDER/" from outside FOLDER/
# (FOLDER relative to DIR)
private_includes() {
	(cd "$1" && grep -rl --include='*.h' -m1 '^/\* [a-z_]*\.h - private to [a-z_/]*/' . 2>/dev/null | sed 's#^\./##' |
		while read -r h; do
			own=$(head -n 1 "$h" | sed -n 's#^/\* [a-z_]*\.h - private to \([a-z_/]*/\).*#\1#p')
			room=${h%%/*}
			grep -rln --include='*.[ch]' "^#include \"\(${h#*/}\|$(basename "$h")\)\"" . 2>/dev/null | sed 's#^\./##' |
				while read -r f; do
					case "$f" in "$room/$own"*) ;; *) echo "$f includes $h, private to $room/$own" ;; esac
				done
		done)
}
pre=$(printf 'study/local/ingest ingest_run\nstudy/local/ingest on_done\nstudy/local/sweep sweep\n' | prefixes)
check floors.selftest.prefix "a second prefix in one object was not reported (got '$pre')" test "$pre" = "study/local/ingest: ingest on"
mkdir -p "$TMP/priv/study/local" "$TMP/priv/study/slurm"
printf '/* x.h - private to local/: made up */\n' >"$TMP/priv/study/local/x.h"
printf '#include "x.h"\n' >"$TMP/priv/study/local/a.c"
printf '#include "local/x.h"\n' >"$TMP/priv/study/slurm/b.c"
priv=$(private_includes "$TMP/priv")
check floors.selftest.private "an include of a private header from another folder was not reported (got '$priv')" \
	test "$priv" = "study/slurm/b.c includes study/local/x.h, private to study/local/"

if ! ls "$BUILD"/lib/*.o >/dev/null 2>&1; then
	fail floors.build "no objects under $BUILD/lib (run make)"
	finish
fi
E=$TMP/edges
edges "$BUILD" >"$E"
check floors.edges "no calls between objects were found in $BUILD" test -s "$E"

bad=$(rooms <"$E")
if [ -z "$bad" ]; then ok floors.rooms.down; else fail floors.rooms.down "calls that point up:
$bad"; fi
bad=$(loops folders <"$E")
if [ -z "$bad" ]; then ok floors.folders.acyclic; else fail floors.folders.acyclic "sub-folders in a circle:
$bad"; fi
bad=$(loops files <"$E")
if [ -z "$bad" ]; then ok floors.files.acyclic; else fail floors.files.acyclic "files in a circle:
$bad"; fi
bad=$(cd "$BUILD" && find lib study -name '*.o' | sort | while read -r o; do
	[ -f "$REPO/${o%.o}.c" ] && nm -g --defined-only "$o" | awk -v o="${o%.o}" '$2 == "T" && $3 != "main" { print o, $3 }'
done | prefixes)
if [ -z "$bad" ]; then ok floors.names.prefix; else fail floors.names.prefix "objects whose exported functions have more than one prefix:
$bad"; fi
bad=$(private_includes "$REPO")
if [ -z "$bad" ]; then ok floors.includes.private; else fail floors.includes.private "$bad"; fi
# Each room's include path names only itself, lib/ and core/ (the makefiles' -I), so
# no source reaches past it with a relative path either.
bad=$(grep -rn '#include "\.\./' core lib study analysis 2>/dev/null)
if [ -z "$bad" ]; then ok floors.includes.relative; else fail floors.includes.relative "$bad"; fi

# core's rooms: every file in one; includes point down; the upper rooms see the public
# face only (the list in core/README.md, one header a line as "- `ROOM/NAME.h`")
check floors.core.rooms "the Makefile names no CORE_ROOMS" test -n "$CORE_ROOMS"
bad=$(find core -type f | sort | roomless "$CORE_ROOMS")
if [ -z "$bad" ]; then ok floors.core.every_file_in_a_room; else fail floors.core.every_file_in_a_room "files of core/ in none of the rooms ($CORE_ROOMS):
$bad"; fi
HEADERS=$(find core -name '*.h' | sort | tr '\n' ' ')
bad=$(includes core | core_up "$CORE_ROOMS" "$HEADERS")
if [ -z "$bad" ]; then ok floors.core.includes_down; else fail floors.core.includes_down "includes of a higher room:
$bad"; fi
PUBLIC=$(awk '/^## The public face/ { on = 1; next } on && /^## / { exit } on' core/README.md | sed -n 's/^- `\([a-z]*\/[a-z_0-9]*\.h\)`.*/\1/p' | tr '\n' ' ')
check floors.core.public_listed "core/README.md lists no public header" test -n "$PUBLIC"
for h in $PUBLIC; do [ -f "core/$h" ] || fail floors.core.public_exists "core/README.md lists $h, which is no file of core/"; done
bad=$(includes lib study analysis | private "$PUBLIC" "$HEADERS")
if [ -z "$bad" ]; then ok floors.core.public_face; else fail floors.core.public_face "the upper rooms include headers core/README.md does not list as public:
$bad"; fi
finish
