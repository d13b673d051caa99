#!/usr/bin/env bash
# docs_lists.sh - the lists the code knows, in the docs: written from the code where the
# doc can be generated, compared with the code where it cannot.
#
#   bash scripts/docs_lists.sh write   # rewrite the generated sections (make docs)
#   bash scripts/docs_lists.sh check   # print "ok ID" / "FAIL ID: why" per list
#
# Generated (between "<!-- docs_lists NAME: begin -->" and "... end -->" markers, or
# study's own "<!-- study columns: begin/end -->"):
#   scene-keys      docs/scene.md        from `bin/shake --params` (core/scene/params.c's table)
#   result-columns  docs/database.md     from `bin/study columns` (lib/results.c's table)
#   test-tiers      docs/testing.md      from `tests/run.sh --tiers` (the scripts' "# tier:" lines)
#   study-options   docs/campaigns.md    from `bin/study options` (study/cli/opts.c's table)
# Checked against the code:
#   tools           docs/analysis.md's table, analysis/README.md's first paragraph and
#                   tests/fuzz/fuzz.c's RUNFILE_TOOLS name exactly the tools of AN_MAIN
#                   (`make print-AN_MAIN`, `make print-campaign-tools`); no other line
#                   names five of them (a second list kept by hand)
#   lib-files       lib/README.md's source tour names every file of lib/, and only those
#   core-files      core/README.md's table of files names every file of core/, and only those
#   python-files    python/README.md's table names every file of python/shakebox/, and only those
#   campaigns       campaigns/README.md names every campaign file (campaigns/, reproduce/, examples/), and only those
#   run-file        docs/output.md's layout table against a run file with every
#                   recorded quantity of `bin/shake --records` on: the same groups; every root and /provenance attribute
#                   and every member of a listed group named in its row
#   docs-map        README.md links every docs/*.md, and every docs/ file it names exists
#   fuzz-inputs     docs/testing.md gives fuzz_quick.sh's number of inputs
# SHAKE and STUDY name the binaries (default: bin/shake, bin/study of this clone).
# DOCS_OVERRIDE=DIR reads a doc from DIR/PATH where that file exists (check only): how
# tests/integration/docs_lists.sh shows that a broken list fails. DOCS_LISTS_CACHE=DIR
# keeps what the code says (the generated lists, the tools, the run file's groups and
# the names in them) in DIR for the next call.
set -u
REPO=$(cd "$(dirname "$0")/.." && pwd)
MODE=${1:-check}
SHAKE=${SHAKE:-$REPO/bin/shake}
STUDY=${STUDY:-$(dirname "$SHAKE")/study}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
nfail=0
# doc PATH: the file to read for the doc at PATH (relative to the clone)
doc() {
	if [ -n "${DOCS_OVERRIDE:-}" ] && [ -f "$DOCS_OVERRIDE/$1" ]; then echo "$DOCS_OVERRIDE/$1"; else echo "$REPO/$1"; fi
}
ok() { echo "ok docs_lists.$1"; }
fail() { echo "FAIL docs_lists.$1: $2"; nfail=$((nfail + 1)); }

# The scene keys as a Markdown table, from the TSV of `shake --params`.
gen_scene_keys() {
	"$SHAKE" --params | awk -F'\t' '
		function bit(f, b) { return int(f / b) % 2 }
		NR == 1 { next }
		{
			f = $8 + 0; infl = ""
			if (bit(f, 1)) infl = infl " prep"
			if (bit(f, 2)) infl = infl " dyn"
			if (bit(f, 4)) infl = infl " len"
			if (bit(f, 8)) infl = infl " out"
			if (bit(f, 32)) infl = infl " driver"
			if (bit(f, 64)) infl = infl " no id"
			sub(/^ /, "", infl)
			gsub(/ /, ", ", infl); gsub(/no, id/, "no id", infl)
			if ($7 != "") range = $7
			else if ($2 == "int" || $2 == "real") range = (bit(f, 16) ? "(" : "[") $5 ", " $6 "]"
			else range = ""
			gsub(/\|/, " \\| ", range)
			def = $4 == "" ? "" : "`" $4 "`"
			help = $9; gsub(/\|/, "\\|", help)
			printf "| `%s` | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, def, range, infl, help
		}' | { printf '| key | type | unit | default | range | influences | meaning |\n|---|---|---|---|---|---|---|\n'; cat; }
}

gen_result_columns() { "$STUDY" columns; }
gen_study_options() { "$STUDY" options; }

gen_test_tiers() { bash "$REPO/tests/run.sh" --tiers; }

# section FILE BEGIN END: the lines between the two marker lines
section() { awk -v b="$2" -v e="$3" '$0 == e { on = 0 } on { print } $0 == b { on = 1 }' "$1"; }

# replace FILE BEGIN END NEWFILE: the lines between the markers become NEWFILE's
replace() {
	grep -qxF "$2" "$1" && grep -qxF "$3" "$1" || { echo "docs_lists: $1: markers '$2' and '$3' missing" >&2; return 1; }
	awk -v b="$2" -v e="$3" -v n="$4" '
		$0 == e { on = 0 }
		!on { print }
		$0 == b { while ((getline l < n) > 0) print l; on = 1 }' "$1" >"$1.tmp" && mv "$1.tmp" "$1"
}

# generated NAME FILE BEGIN END GENERATOR
generated() {
	local name=$1 file=$2 b=$3 e=$4 gen=$5
	if [ -n "${DOCS_LISTS_CACHE:-}" ] && [ -s "$DOCS_LISTS_CACHE/$name.new" ]; then
		cp "$DOCS_LISTS_CACHE/$name.new" "$TMP/$name.new"
	elif ! $gen >"$TMP/$name.new" 2>"$TMP/$name.err" || ! [ -s "$TMP/$name.new" ]; then
		fail "$name" "could not generate it: $(head -c 300 "$TMP/$name.err")"
		return
	elif [ -n "${DOCS_LISTS_CACHE:-}" ]; then
		cp "$TMP/$name.new" "$DOCS_LISTS_CACHE/$name.new"
	fi
	if [ "$MODE" = write ]; then
		replace "$REPO/$file" "$b" "$e" "$TMP/$name.new" && echo "docs_lists: $file: $name written"
		return
	fi
	section "$(doc "$file")" "$b" "$e" >"$TMP/$name.doc"
	if cmp -s "$TMP/$name.new" "$TMP/$name.doc"; then
		ok "$name.current"
	else
		fail "$name.current" "$file differs from the code (make docs rewrites it): $(diff "$TMP/$name.doc" "$TMP/$name.new" | grep '^[<>]' | head -n 4 | cut -c1-160 | tr '\n' ' ')"
	fi
}

# same_set NAME WHAT CODE-LIST DOC-LIST (one name a line each)
same_set() {
	local extra missing
	missing=$(comm -23 <(sort -u "$3") <(sort -u "$4") | tr '\n' ' ')
	extra=$(comm -13 <(sort -u "$3") <(sort -u "$4") | tr '\n' ' ')
	if [ -z "$missing$extra" ]; then
		ok "$1"
	else
		fail "$1" "$2:${missing:+ missing from the doc: $missing}${extra:+ in the doc but not in the code: $extra}"
	fi
}

generated scene-keys docs/scene.md '<!-- docs_lists scene-keys: begin -->' '<!-- docs_lists scene-keys: end -->' gen_scene_keys
generated result-columns docs/database.md '<!-- study columns: begin -->' '<!-- study columns: end -->' gen_result_columns
generated test-tiers docs/testing.md '<!-- docs_lists test-tiers: begin -->' '<!-- docs_lists test-tiers: end -->' gen_test_tiers
generated study-options docs/campaigns.md '<!-- docs_lists study-options: begin -->' '<!-- docs_lists study-options: end -->' gen_study_options
[ "$MODE" = write ] && exit 0

# code NAME FUNC: what the code says (FUNC's output) in $TMP/NAME.code; with
# DOCS_LISTS_CACHE, taken from there when an earlier call kept it, else kept there
code() {
	if [ -n "${DOCS_LISTS_CACHE:-}" ] && [ -f "$DOCS_LISTS_CACHE/$1.code" ]; then
		cp "$DOCS_LISTS_CACHE/$1.code" "$TMP/$1.code"
		return
	fi
	$2 >"$TMP/$1.code" || return 1
	[ -z "${DOCS_LISTS_CACHE:-}" ] || cp "$TMP/$1.code" "$DOCS_LISTS_CACHE/$1.code"
}

# --- the tools: analysis/analysis.mk's AN_MAIN ---
tools_code() { make -s --no-print-directory -C "$REPO" print-AN_MAIN | tr ' ' '\n' | grep .; }
code tools tools_code
awk '/<!-- docs_lists tools:/ { on = 1; next } on && /^\|/ { print; next } on && /^$/ && n++ { exit }' \
	"$(doc docs/analysis.md)" | sed -n 's/^| `bin\/\([a-z_]*\)` |.*/\1/p' >"$TMP/tools.doc"
same_set tools.docs_analysis "docs/analysis.md's table of tools" "$TMP/tools.code" "$TMP/tools.doc"
awk 'NR > 1 && /^$/ && seen { exit } /^[^#]/ { seen = 1; print }' "$(doc analysis/README.md)" |
	grep -o '`bin/[a-z_]*`' | tr -d '`' | sed 's#bin/##' >"$TMP/tools.room"
same_set tools.analysis_readme "analysis/README.md's first paragraph" "$TMP/tools.code" "$TMP/tools.room"

# tests/fuzz/fuzz.c's RUNFILE_TOOLS, the one copy in C: the tools that read a campaign's
# runs (`make print-campaign-tools`) and study
ctools_code() {
	local t
	t=$(make -s --no-print-directory -C "$REPO" print-campaign-tools 2>"$TMP/make.err") && [ -n "$t" ] || return 1
	printf '%s\n' $t study
}
if code campaign-tools ctools_code; then
	awk '/RUNFILE_TOOLS\[\] = \{/ { on = 1 } on { print } on && /\};/ { exit }' "$(doc tests/fuzz/fuzz.c)" |
		grep -o '"[a-z_]*"' | tr -d '"' >"$TMP/tools.fuzz"
	same_set tools.fuzz_c "tests/fuzz/fuzz.c's RUNFILE_TOOLS" "$TMP/campaign-tools.code" "$TMP/tools.fuzz"
else
	fail tools.fuzz_c "make print-campaign-tools named no tool: $(head -c 300 "$TMP/make.err")"
fi
# No other copy: a line of the sources, scripts or docs that names five or more tools
# as words is a list kept by hand; it reads `make print-tools` or
# `make print-campaign-tools` instead. Only the places above may: AN_MAIN itself,
# analysis/README.md's first paragraph, fuzz.c's RUNFILE_TOOLS.
files=()
while read -r f; do
	if [ -n "${DOCS_OVERRIDE:-}" ] && [ -f "$DOCS_OVERRIDE/$f" ]; then files+=("$DOCS_OVERRIDE/$f"); else files+=("$REPO/$f"); fi
done < <(cd "$REPO" && ls Makefile README.md REPRODUCTION.md 2>/dev/null && find core lib study analysis scripts tests docs campaigns \
	-type f \( -name '*.[ch]' -o -name '*.sh' -o -name '*.md' -o -name '*.mk' -o -name '*.campaign' -o -name '*.py' \) 2>/dev/null | sort)
copies=$(awk -v t="$(tr '\n' ' ' <"$TMP/tools.code")" -v r="$REPO/" -v o="${DOCS_OVERRIDE:-/nonexistent}/" '
	BEGIN { n = split(t, T, " ") }
	{ c = 0; for (i = 1; i <= n; i++) if (match($0, "(^|[^A-Za-z0-9_./-])" T[i] "([^A-Za-z0-9_-]|$)")) c++
	  if (c >= 5) { f = FILENAME; if (index(f, r) == 1) f = substr(f, length(r) + 1); else if (index(f, o) == 1) f = substr(f, length(o) + 1)
	                print f ":" FNR } }' "${files[@]}" |
	grep -vxE 'analysis/analysis\.mk:[0-9]+|analysis/README\.md:[0-9]+|tests/fuzz/fuzz\.c:[0-9]+' | tr '\n' ' ')
if [ -z "$copies" ]; then ok tools.no_copy; else fail tools.no_copy "a second list of the tools, kept by hand (read make print-tools): $copies"; fi

# --- the files of lib/: lib/README.md's source tour names each, and only those ---
# tour_files MARKER DOC: the files a table after "<!-- docs_lists MARKER:" names in its
# first column, one a line ("name.[ch]" as name.c and name.h)
tour_files() {
	awk -v m="<!-- docs_lists $1:" 'index($0, m) == 1 { on = 1; next } on && /^\|/ { print; next } on && /^$/ && n++ { exit }' \
		"$(doc "$2")" | awk -F'|' 'NR > 2 { print $2 }' | grep -o '`[^`]*`' | tr -d '`' |
		awk '{ if (sub(/\.\[ch\]$/, "")) { print $0 ".c"; print $0 ".h" } else print }'
}
(cd "$REPO/lib" && ls) >"$TMP/lib.code"
tour_files lib-files lib/README.md >"$TMP/lib.doc"
same_set lib-files "lib/README.md's source tour" "$TMP/lib.code" "$TMP/lib.doc"

# --- the files of the Python package ---
(cd "$REPO/python" && find shakebox -type f -name '*.py' | sort) >"$TMP/python.code"
tour_files python-files python/README.md >"$TMP/python.doc"
same_set python-files "python/README.md's table of files" "$TMP/python.code" "$TMP/python.doc"

# --- the files of core/ ---
(cd "$REPO/core" && find . -type f ! -name README.md | sed "s#^\./##" | sort) >"$TMP/core.code"
awk '/<!-- docs_lists core-files:/ { on = 1; next } on && /^\|/ { print; next } on && /^$/ && n++ { exit }' \
	"$(doc core/README.md)" | awk -F'|' 'NR > 2 { print $2 }' | grep -o '`[^`]*`' | tr -d '`' |
	while read -r f; do
		case "$f" in
		*.\[ch\]) echo "${f%.\[ch\]}.c"; echo "${f%.\[ch\]}.h" ;;
		*) echo "$f" ;;
		esac
	done >"$TMP/core.doc"
same_set core-files "core/README.md's table of files" "$TMP/core.code" "$TMP/core.doc"

# --- the campaign files ---
(cd "$REPO/campaigns" && ls *.campaign reproduce/*.campaign examples/*.campaign) >"$TMP/camp.code"
grep -o '^| `[^`]*\.campaign`' "$(doc campaigns/README.md)" | sed 's/^| `//; s/`$//' >"$TMP/camp.doc"
same_set campaigns "campaigns/README.md's tables" "$TMP/camp.code" "$TMP/camp.doc"

# --- the run file's layout ---
# every recorded quantity on, from the engine's table of them (shake --records: a rate
# key at 20 Hz, a count per period at 4, a switch yes), two intruders (/intruders)
write_run_file() {
	local all_on
	[ -s "$TMP/all.h5" ] && return
	all_on=$("$SHAKE" --records | awk -F'\t' 'NR > 1 { print $2 "=" ($3 == "rate" ? 20 : $3 == "phase" ? 4 : "yes") }')
	[ -n "$all_on" ] && (cd "$TMP" && "$SHAKE" n_grains=40 width=15 radius_ratio=2 n_intruders=2 intruder_place=column duration=0.6 frequency=5 amplitude=1 \
		settle_min=0.1 settle_ke=1 field_periods=1 $all_on output=all.h5 >run.log 2>&1) && [ -s "$TMP/all.h5" ]
}
# its groups, one a line
run_groups() {
	write_run_file || return 1
	h5ls "$TMP/all.h5" | awk '$2 == "Group" { print "/" $1 }' | grep -vx '/particles\|/observables'
	for g in particles observables; do h5ls "$TMP/all.h5/$g" | awk -v g="$g" '$2 == "Group" { print "/" g "/" $1 }'; done
}
# what the doc must name in its groups' rows, as "GROUP<TAB>SEP<TAB>NAME": the root's and
# /provenance's own attributes (SEP @), and every member of /particles/*, /observables/*
# and /final (SEP /)
run_names() {
	local g
	write_run_file || return 1
	for g in / /provenance; do
		h5dump -H -g "$g" "$TMP/all.h5" 2>/dev/null | awk -v d="$([ "$g" = / ] && echo 3 || echo 6)" -v g="$g" '
			match($0, /^ *ATTRIBUTE "/) && RLENGTH - 11 == d { s = $0; sub(/^ *ATTRIBUTE "/, "", s); sub(/".*/, "", s); print g "\t@\t" s }'
	done
	while read -r g; do
		case "$g" in /particles/* | /observables/* | /final) ;; *) continue ;; esac
		h5ls "$TMP/all.h5$g" 2>/dev/null | awk -v g="$g" '{ print g "\t/\t" $1 }'
	done <"$TMP/groups.code"
}
if code groups run_groups && code names run_names; then
	grep '^| `/' "$(doc docs/output.md)" >"$TMP/rows"
	sed 's/^| `\([^`]*\)`.*/\1/' "$TMP/rows" | grep -vx '/' >"$TMP/groups.doc"
	same_set run-file.groups "docs/output.md's layout table" "$TMP/groups.code" "$TMP/groups.doc"
	# the names that their group's row (the first row whose first cell is the group) does
	# not hold as a word, as " GROUP SEP NAME"
	bad=$(awk -F'\t' '
		FNR == NR { split($0, c, "`"); if (!(c[2] in row)) row[c[2]] = $0; next }
		{
			g = $1; n = $3; hit = 0; rest = row[g]
			while ((i = index(rest, n)) > 0) {
				b = i > 1 ? substr(rest, i - 1, 1) : " "; a = substr(rest, i + length(n), 1)
				if (b !~ /[A-Za-z0-9_]/ && a !~ /[A-Za-z0-9_]/) { hit = 1; break }
				rest = substr(rest, i + 1)
			}
			if (!hit) printf " %s%s%s", g, $2, n
		}' "$TMP/rows" "$TMP/names.code")
	[ -z "$bad" ] && ok run-file.members ||
		fail run-file.members "in the run file but not in docs/output.md's row of its group:$bad"
else
	fail run-file "the engine did not write a run file: $(tail -n 3 "$TMP/run.log" 2>/dev/null)"
fi

# --- the number of inputs of make check's fuzz run ---
n=$(sed -n 's/^N="${FUZZ_QUICK_INPUTS:-\([0-9]*\)}"$/\1/p' "$REPO/tests/integration/fuzz_quick.sh")
if [ -z "$n" ]; then
	fail fuzz-inputs "no N=\"\${FUZZ_QUICK_INPUTS:-NUMBER}\" line in tests/integration/fuzz_quick.sh"
elif grep -q "fuzz_quick.sh\` runs $n inputs" "$(doc docs/testing.md)"; then
	ok fuzz-inputs
else
	fail fuzz-inputs "docs/testing.md does not say that fuzz_quick.sh runs $n inputs (its FUZZ_QUICK_INPUTS default)"
fi

# --- the map of the docs in README.md ---
(cd "$REPO" && ls docs/*.md) >"$TMP/map.code"
grep -o 'docs/[A-Za-z0-9_]*\.md' "$(doc README.md)" | sort -u >"$TMP/map.doc"
same_set docs-map "README.md's map of docs/" "$TMP/map.code" "$TMP/map.doc"

[ "$nfail" -eq 0 ]
